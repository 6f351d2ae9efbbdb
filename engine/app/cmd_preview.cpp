#include <cmath>
#include <cstdio>

#include "engine/app/commands.h"
#include "engine/tools/gallery/contact_sheet.h"
#include "engine/present/image_io.h"
#include "generators/asset/asset_io.h"

namespace forest::app {

int run_preview(const PreviewArgs& args) {
  check_output_path(args.out, "--out");
  TreeModel model = load_glb(args.model);
  vk::Context ctx;
  vk::ContextOptions options;
  options.device = args.device;
  options.validation = vk::validation_from_env();
  int code = 0;
  try {
    vk::create_context(ctx, options);
    TurntableOptions t;
    t.size = args.size;
    t.views = args.views;
    std::vector<FrameImage> views = render_turntable(ctx, model, t);
    FrameImage sheet = compose_grid(views, uint32_t(std::ceil(std::sqrt(double(views.size())))));
    if (ctx.validation_messages > 0) {
      std::fprintf(stderr, "forest: %u Vulkan validation message(s); no image written\n", ctx.validation_messages.load());
      code = 1;
    } else {
      write_image(sheet, args.out);
      std::printf("wrote %s: %u views of %s (%zu branch triangles, %zu leaves)\n", args.out.c_str(), args.views,
                  args.model.c_str(), model.branches.indices.size() / 3, model.leaves.size());
    }
  } catch (...) {
    vk::destroy_context(ctx);
    throw;
  }
  vk::destroy_context(ctx);
  return code;
}

}  // namespace forest::app
