// forest export MODEL.glb --out X.glb [--flatten]: a baked or unbaked model as client files
// (glb_export.h): one file per branch LOD, no engine data, leaves instanced or flattened.
#include <cstdio>

#include "engine/app/commands.h"
#include "engine/app/progress.h"
#include "engine/present/image_io.h"
#include "generators/asset/asset_io.h"
#include "generators/asset/glb_export.h"
#include "generators/core/input_error.h"

namespace forest::app {

int run_export(const ExportArgs& a) {
  namespace fs = std::filesystem;
  fs::path out = a.out;
  if (out.extension() != ".glb") throw InputError(a.out, 0, "--out", "must name a .glb file");
  check_output_path(out, "--out");
  TreeModel model = load_glb(a.model);
  ExportOptions options;
  options.flatten = a.flatten;
  ProgressBar bar("export");
  bar.update(0.0);
  options.progress = [&bar](double f) { bar.update(f); };
  std::vector<ExportedLod> lods = export_model(model, out, options);  // all files, or none
  bar.finish();
  for (const ExportedLod& e : lods)
    std::printf("%s: node %s, %zu branch triangles, %zu leaves (%zu triangles, %s), error %.4f m, screen coverage <= %.4f\n",
                e.file.c_str(), e.node.c_str(), e.branch_triangles, e.leaves, e.leaf_triangles,
                a.flatten ? "one mesh, COLOR_0" : "EXT_mesh_gpu_instancing, _COLOR_0", double(e.error),
                double(e.screen_coverage));
  return 0;
}

}  // namespace forest::app
