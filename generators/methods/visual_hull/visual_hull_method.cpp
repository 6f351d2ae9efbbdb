// Species keys of method "visual-hull" (besides the shared image keys of image_species.h):
//   seed; voxels (hull grid cells along the longest side), tips_per_view, extra_branches
//   (skeleton); years, internode (m, 0 = 3.5 % of the bounds height), branch_angle,
//   regrow_factor, tropism, jitter (deg), starve, fill_target, max_nodes (growth).
#include "generators/methods/visual_hull/visual_hull_method.h"

#include "generators/methods/common/image_species.h"
#include "generators/methods/common/image_synthetic.h"
#include "generators/methods/visual_hull/visual_hull_growth.h"

namespace forest {

TreeModel generate_visual_hull(const TomlTable& t, const std::string& species_name,
                               const GenerateOptions& options) {
  check_image_species_keys(t, {"voxels", "tips_per_view", "extra_branches", "years", "internode",
                               "branch_angle", "regrow_factor", "tropism", "jitter", "starve",
                               "fill_target", "max_nodes"});
  t.string("name", "");
  uint64_t seed = options.seed.value_or(uint64_t(t.integer("seed", 1, 0, int64_t(1) << 53)));
  SkeletonParams sp;
  sp.voxels = int(t.integer("voxels", sp.voxels, 8, 128));
  sp.tips_per_view = int(t.integer("tips_per_view", sp.tips_per_view, 0, 64));
  sp.extra_branches = int(t.integer("extra_branches", sp.extra_branches, 0, 64));
  GrowthParams gp;
  gp.years = int(t.integer("years", gp.years, 0, 30));
  double internode = t.number("internode", 0.0, 0.0, 100.0);
  gp.branch_angle_deg = t.number("branch_angle", gp.branch_angle_deg, 0.0, 120.0);
  gp.regrow_factor = t.number("regrow_factor", gp.regrow_factor, 0.05, 0.99);
  gp.tropism = t.number("tropism", gp.tropism, -1.0, 1.0);
  gp.jitter_deg = t.number("jitter", gp.jitter_deg, 0.0, 90.0);
  gp.starve = t.number("starve", gp.starve, 0.0, 1.0);
  gp.fill_target = t.number("fill_target", gp.fill_target, 0.0, 1.0);
  gp.max_nodes = size_t(t.integer("max_nodes", int64_t(gp.max_nodes), 100, 500000));
  TreeLook look;
  look.tip_radius = 0.006f;
  look.pipe_exponent = 2.4f;
  look.leaves.size = 0.12f;
  look.leaves.along = 1;
  look = read_tree_look(t, look);
  ViewSet views = read_image_input(t);

  gp.internode = internode > 0.0 ? internode : 0.035 * views.bounds.size().y;
  gp.min_length = 0.15 * gp.internode;
  VoxelGrid grid = voxelize_hull(views, sp.voxels);
  HullSkeleton skeleton = hull_skeleton(views, grid, sp);
  if (skeleton.graph.nodes.size() < 2)
    t.fail(t.has("views") ? "views" : "crown", "the visual hull of the masks is empty or too thin for a skeleton");
  GrowthState state = start_growth(skeleton, gp);
  auto reports = grow(state, views, grid, gp, seed);
  TreeGraph graph = growth_graph(state);

  nlohmann::json stats;
  stats["views"] = views.views.size();
  stats["skeleton_nodes"] = skeleton.graph.nodes.size();
  stats["skeleton_tips"] = skeleton.marked.size();
  stats["years"] = reports.size();
  size_t pruned = 0;
  for (const YearReport& r : reports) pruned += r.pruned;
  stats["pruned"] = pruned;
  stats["fill"] = reports.empty() ? 0.0 : reports.back().fill;
  return finish_image_tree(std::move(graph), look, views, t, "visual-hull", species_name, seed, stats);
}

const char* visual_hull_default_species_text() {
  return R"toml(method = "visual-hull"
# Seed 003 (Shlyakhter et al. 2001): a trunk and four ellipsoid crown lobes seen by 8
# pinhole cameras on a circle, masks rendered in memory; hull -> skeleton -> L-system.
name = "visual_hull_lobes"
seed = 1
crown = { shape = "lobes", height = 8.0, width = 7.0, trunk_height = 2.5, trunk_radius = 0.3, views = 8, resolution = 128, camera = "perspective" }
years = 7
leaf_size = 0.14
leaves_along = 1
)toml";
}

void visual_hull_make_inputs(const std::filesystem::path& dir) {
  CrownSpec ellipsoid;
  ellipsoid.shape = "ellipsoid";
  ellipsoid.height = 9.0;
  ellipsoid.width = 7.0;
  ellipsoid.depth = 5.0;
  ellipsoid.views = 8;
  ellipsoid.perspective = true;
  write_view_set(synthesize_view_set(ellipsoid), dir / "ellipsoid");
  CrownSpec cone = ellipsoid;
  cone.shape = "cone";
  cone.height = 12.0;
  cone.width = 5.0;
  cone.depth = 5.0;
  cone.trunk_height = 1.5;
  write_view_set(synthesize_view_set(cone), dir / "cone");
}

}  // namespace forest
