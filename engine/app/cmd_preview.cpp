#include <cmath>
#include <cstdio>

#include "engine/app/app_common.h"
#include "engine/app/commands.h"
#include "engine/tools/gallery/contact_sheet.h"
#include "engine/present/image_io.h"
#include "generators/asset/asset_io.h"

namespace forest::app {

int run_preview(const PreviewArgs& args) {
  check_output_path(args.out, "--out");
  TreeModel model = load_glb(args.model);
  CommandContext context(context_options(args.device, false));
  TurntableOptions t;
  t.size = args.size;
  t.views = args.views;
  std::vector<FrameImage> views = render_turntable(context.ctx, model, t);
  FrameImage sheet = compose_grid(views, uint32_t(std::ceil(std::sqrt(double(views.size())))));
  if (validation_failed(context.ctx, "image")) return 1;
  write_image(sheet, args.out);
  std::printf("wrote %s: %u views of %s (%zu branch triangles, %zu leaves)\n", args.out.c_str(), args.views,
              args.model.c_str(), model.branches.indices.size() / 3, model.leaves.size());
  return 0;
}

}  // namespace forest::app
