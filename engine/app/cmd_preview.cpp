#include <cmath>
#include <cstdio>

#include "engine/app/app_common.h"
#include "engine/app/commands.h"
#include "engine/tools/gallery/contact_sheet.h"
#include "engine/present/image_io.h"
#include "generators/asset/asset_io.h"
#include "generators/core/input_error.h"

namespace forest::app {

int run_preview(const PreviewArgs& args) {
  check_output_path(args.out, "--out");
  TreeModel model = load_glb(args.model);
  CommandContext context(context_options(args.device, false));
  TurntableOptions t;
  t.size = args.size;
  t.views = args.views;
  std::vector<FrameImage> views;
  uint32_t columns = 0;
  if (args.bark_lods) {
    // Each level as its own leafless model seen from the first view: what the cull pass
    // switches between (structural_lod.h).
    t.views = 1;
    std::vector<const Mesh*> levels{&model.branches};
    for (const MeshLod& l : model.branch_lods) levels.push_back(&l.mesh);
    for (const Mesh* level : levels) {
      TreeModel bark = model;
      bark.branches = *level;
      bark.branch_lods.clear();
      bark.leaves.clear();
      std::vector<FrameImage> v = render_turntable(context.ctx, bark, t);
      views.push_back(std::move(v.front()));
      std::printf("LOD%zu: %zu triangles\n", views.size() - 1, level->indices.size() / 3);
    }
    columns = uint32_t(views.size());
  } else if (args.impostor) {
    // The mesh above, its impostor below (impostor_bake.h), from the same cameras.
    if (!model.impostor.present())
      throw InputError(args.model, 0, "", "has no impostor (bake it: forest bake)");
    views = render_turntable(context.ctx, model, t);
    t.settings.impostors = ImpostorMode::always;
    for (FrameImage& v : render_turntable(context.ctx, model, t)) views.push_back(std::move(v));
    columns = t.views;
    for (size_t b = 0; b < model.impostor.q.size(); ++b)
      std::printf("impostor Q at %g px: %.3f\n", double(pr_size(model.bake.pr_tables ? model.bake.pr_tables->size0 : 512.0f, uint32_t(b))),
                  double(model.impostor.q[b]));
  } else {
    views = render_turntable(context.ctx, model, t);
    columns = uint32_t(std::ceil(std::sqrt(double(views.size()))));
  }
  FrameImage sheet = compose_grid(views, columns);
  if (validation_failed(context.ctx, "image")) return 1;
  write_image(sheet, args.out);
  std::printf("wrote %s: %zu views of %s (%zu branch triangles, %zu leaves)\n", args.out.c_str(), views.size(),
              args.model.c_str(), model.branches.indices.size() / 3, model.leaves.size());
  return 0;
}

}  // namespace forest::app
