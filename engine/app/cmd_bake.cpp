#include <chrono>
#include <cstdio>

#include "engine/app/commands.h"
#include "engine/app/progress.h"
#include "engine/render/pr_bake.h"
#include "generators/bake/asset_io.h"
#include "generators/bake/hull.h"
#include "generators/bake/priority.h"
#include "generators/common/input_error.h"

namespace forest::app {

BakeResult bake_model(TreeModel& model, const BakeArgs& args) {
  using clock = std::chrono::steady_clock;
  auto t0 = clock::now();
  std::optional<Priority> priority = parse_priority(args.priority);
  if (!priority) throw InputError("--priority", 0, "", "unknown priority '" + args.priority + "' (random, density, orientation, combined, layered)");
  uint64_t seed = args.seed ? *args.seed : model.meta.value("seed", uint64_t(1));

  HullParams hp;
  hp.seed = seed;
  Hull hull = build_hull(model.leaves, plant_height(model), hp);
  attach_hull(model, hull);
  apply_priority(model, hull, *priority, seed);
  auto t_hull = clock::now();

  vk::Context ctx;
  vk::ContextOptions options;
  options.device = args.device;
  options.validation = vk::validation_from_env();
  PrMeasurement pm;
  try {
    vk::create_context(ctx, options);
    ProgressBar bar("bake: measuring PR");
    PrBakeOptions po;
    po.resolution = args.resolution;
    po.views = args.views;
    po.progress = [&](double f) { bar.update(f); };
    pm = measure_pr_tables(ctx, model, po);
    bar.finish();
    if (ctx.validation_messages > 0)
      throw vk::VkFailure(std::to_string(ctx.validation_messages.load()) + " Vulkan validation message(s) during bake");
  } catch (...) {
    vk::destroy_context(ctx);
    throw;
  }
  vk::destroy_context(ctx);
  pm.tables.priority = args.priority;
  model.meta["pr_tables"] = to_json(pm.tables);
  nlohmann::json samples = nlohmann::json::array();  // the PR diagram behind the tables
  for (const PrSample& ps : pm.samples)
    samples.push_back({ps.lambda, ps.scale, ps.pr.precision(), ps.pr.recall()});
  model.meta["pr_samples"] = samples;
  model.meta["baked"] = true;
  BakeResult r;
  r.measurement = std::move(pm);
  r.hull_seconds = std::chrono::duration<double>(t_hull - t0).count();
  r.pr_seconds = std::chrono::duration<double>(clock::now() - t_hull).count();
  r.hull_triangles = hull.mesh.indices.size() / 3;
  return r;
}

int run_bake(const BakeArgs& args) {
  std::filesystem::path out = args.out.empty() ? args.model : args.out;
  TreeModel model = load_glb(args.model);
  BakeResult r = bake_model(model, args);
  save_glb(model, out);
  const PrTables& t = r.measurement.tables;
  std::printf("baked %s -> %s: %zu leaves (%s order), hull %zu triangles, %d views at %d px; "
              "hull+order %.1f s, PR %.1f s\n",
              args.model.c_str(), out.c_str(), model.leaves.size(), args.priority.c_str(), r.hull_triangles,
              t.views, t.resolution, r.hull_seconds, r.pr_seconds);
  const PrBakeStats& st = r.measurement.stats;
  std::printf("PR: %u pruned renders in %u submits; references %.1f s, pruned renders + counts %.1f s\n", st.renders,
              st.submits, st.reference_seconds, st.compare_seconds);
  std::printf("s_opt at lambda 0.1/0.2/0.5: %.2f %.2f %.2f (1/lambda: 10 5 2); Q there: %.3f %.3f %.3f\n",
              double(t.s_opt[2]), double(t.s_opt[4]), double(t.s_opt[10]), double(t.q_opt[2]), double(t.q_opt[4]),
              double(t.q_opt[10]));
  return 0;
}

}  // namespace forest::app
