#include "engine/tools/bake/tree_bake.h"

#include "engine/tools/bake/impostor_bake.h"

#include <chrono>

#include "generators/bake/hull/hull.h"
#include "generators/bake/hull/hull_depth.h"
#include "generators/bake/priority/priority.h"
#include "generators/core/input_error.h"

namespace forest {

TreeBakeResult bake_tree_model(vk::Context& ctx, TreeModel& model, const TreeBakeSettings& settings) {
  using clock = std::chrono::steady_clock;
  auto t0 = clock::now();
  std::optional<Priority> priority = parse_priority(settings.priority);
  if (!priority)
    throw InputError("--priority", 0, "", "unknown priority '" + settings.priority + "' (random, density, orientation, combined, layered)");
  uint64_t seed = settings.seed ? *settings.seed : model.meta.value("seed", uint64_t(1));

  HullParams hp;
  hp.seed = seed;
  Hull hull = build_hull(model.leaves, plant_height(model), hp);
  attach_hull(model, hull);
  auto t_hull_mesh = clock::now();
  attach_crown_light(model, hull);  // per-leaf depths; apply_priority reorders them with the leaves
  auto t_crown = clock::now();
  apply_priority(model, hull, *priority, seed);
  auto t_hull = clock::now();

  uint32_t messages_before = ctx.validation_messages.load();
  PrBakeOptions po;
  po.size0 = settings.resolution;
  po.views = settings.views;
  po.progress = settings.progress;
  PrMeasurement pm = measure_pr_tables(ctx, model, po);
  auto t_pr = clock::now();
  pm.tables.priority = settings.priority;
  model.bake.pr_tables = pm.tables;
  model.bake.pr_samples.clear();  // the PR diagram behind the tables
  for (const PrSample& ps : pm.samples)
    for (uint32_t b = 0; b < PR_SIZES; ++b)
      model.bake.pr_samples.push_back({ps.lambda, ps.scale, pr_size(pm.tables.size0, b), ps.pr[b].precision(),
                                       ps.pr[b].recall()});
  // After the tables: the impostor's views prune by them (impostor_bake.cpp).
  model.impostor = {};
  if (settings.impostor) attach_impostor(ctx, model, settings.views, settings.resolution);
  if (ctx.validation_messages > messages_before)
    throw vk::VkFailure(std::to_string(ctx.validation_messages.load() - messages_before) +
                        " Vulkan validation message(s) during bake");
  TreeBakeResult r;
  r.measurement = std::move(pm);
  r.hull_seconds = std::chrono::duration<double>(t_hull - t0).count();
  r.crown_seconds = std::chrono::duration<double>(t_crown - t_hull_mesh).count();
  r.pr_seconds = std::chrono::duration<double>(t_pr - t_hull).count();
  r.impostor_seconds = std::chrono::duration<double>(clock::now() - t_pr).count();
  r.hull_triangles = hull.mesh.indices.size() / 3;
  return r;
}

}  // namespace forest
