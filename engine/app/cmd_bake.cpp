#include <chrono>
#include <cstdio>

#include "engine/app/app_common.h"
#include "engine/app/commands.h"
#include "engine/app/progress.h"
#include "engine/tools/bake/pr_bake.h"
#include "engine/tools/bake/tree_bake.h"
#include "generators/asset/asset_io.h"
#include "generators/bake/priority/priority.h"
#include "generators/core/input_error.h"

namespace forest::app {

BakeResult bake_model(TreeModel& model, const BakeArgs& args) {
  TreeBakeSettings settings;
  settings.priority = args.priority;
  settings.seed = args.seed;
  settings.views = args.views;
  settings.resolution = args.resolution;
  if (!parse_priority(args.priority))  // before creating a Vulkan context
    throw InputError("--priority", 0, "", "unknown priority '" + args.priority + "' (random, density, orientation, combined, layered)");
  TreeBakeResult tb;
  {
    CommandContext context(context_options(args.device, false));
    ProgressBar bar("bake: measuring PR");
    settings.progress = [&](double f) { bar.update(f); };
    tb = bake_tree_model(context.ctx, model, settings);
    bar.finish();
  }
  BakeResult r;
  r.measurement = std::move(tb.measurement);
  r.hull_seconds = tb.hull_seconds;
  r.pr_seconds = tb.pr_seconds;
  r.impostor_seconds = tb.impostor_seconds;
  r.hull_triangles = tb.hull_triangles;
  return r;
}

int run_bake(const BakeArgs& args) {
  std::filesystem::path out = args.out.empty() ? args.model : args.out;
  TreeModel model = load_glb(args.model);
  BakeResult r = bake_model(model, args);
  save_glb(model, out);
  const PrTables& t = r.measurement.tables;
  std::printf("baked %s -> %s: %zu leaves (%s order), hull %zu triangles, %d views at %d px (tree %g ... %g px "
              "across); hull+order %.1f s, PR %.1f s\n",
              args.model.c_str(), out.c_str(), model.leaves.size(), args.priority.c_str(), r.hull_triangles,
              t.views, t.resolution, double(t.size0), double(pr_size(t.size0, PR_SIZES - 1)), r.hull_seconds,
              r.pr_seconds);
  if (model.impostor.present()) {
    std::printf("impostor: %d x %d views of %d px, %.1f s, coverage cutoff %.2f; Q against full detail at",
                IMPOSTOR_GRID, IMPOSTOR_GRID, IMPOSTOR_VIEW_SIZE, r.impostor_seconds, double(model.impostor.cutoff));
    for (uint32_t b = 0; b < model.impostor.q.size(); ++b)
      std::printf(" %g px %.3f%s", double(pr_size(t.size0, b)), double(model.impostor.q[b]), b + 1 < PR_SIZES ? "," : "\n");
  }
  const PrBakeStats& st = r.measurement.stats;
  std::printf("PR: %u pruned renders in %u submits; references %.1f s, pruned renders + counts %.1f s\n", st.renders,
              st.submits, st.reference_seconds, st.compare_seconds);
  for (uint32_t b = 0; b < PR_SIZES; ++b) {
    const PrSizeTables& s = t.sizes[b];
    std::printf("%5g px: s_opt at lambda 0.1/0.2/0.5: %.2f %.2f %.2f (1/lambda: 10 5 2); Q there: %.3f %.3f %.3f\n",
                double(pr_size(t.size0, b)), double(s.s_opt[2]), double(s.s_opt[4]), double(s.s_opt[10]),
                double(s.q_opt[2]), double(s.q_opt[4]), double(s.q_opt[10]));
  }
  return 0;
}

}  // namespace forest::app
