// Species keys of method "visual-hull" (besides the shared image keys of image_species.h):
//   seed; voxels (hull grid cells along the longest side), tips_per_view, extra_branches
//   (skeleton); years, internode (m, 0 = 3.5 % of the bounds height), branch_angle,
//   regrow_factor, tropism, jitter (deg), starve, fill_target, max_nodes (growth).
#include "generators/methods/visual_hull/visual_hull_method.h"

#include "generators/methods/common/image_species.h"
#include "generators/methods/common/image_synthetic.h"
#include "generators/methods/visual_hull/visual_hull_growth.h"

namespace forest {

namespace {

// The method's own species keys; the registry adds the common and the look keys.
constexpr std::string_view kKeys[] = {
    "voxels", "tips_per_view", "extra_branches", "years", "internode", "branch_angle",
    "regrow_factor", "tropism", "jitter", "starve", "fill_target", "max_nodes",
    FOREST_IMAGE_SPECIES_KEYS};

Skeleton skeleton_pass(const TomlTable& t, uint64_t seed) {
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
  const ImageTreeStyle style = read_image_tree_style(
      t, {.tip_radius = 0.006f, .pipe_exponent = 2.4f});
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
  return finish_image_tree(std::move(graph), style, views, std::move(stats));
}

// Built-in preset: a synthetic lobed crown rendered into 8 perspective masks in memory.
const char* builtin_preset() {
  return R"toml(method = "visual-hull"
# Seed 003 (Shlyakhter et al. 2001): a trunk and four ellipsoid crown lobes seen by 8
# pinhole cameras on a circle, masks rendered in memory; hull -> skeleton -> L-system.
name = "visual_hull_lobes"
seed = 1
crown = { shape = "lobes", height = 8.0, width = 7.0, trunk_height = 2.5, trunk_radius = 0.3, views = 8, resolution = 128, camera = "perspective" }
years = 7

# foliage: a method demo: the shared foliage model, blade 6-10 cm on shoots of 25-35 cm.
leaf_shape = "ovate"
foliage = "shoots"
leaf_size = 0.08
leaf_size_jitter = 0.2
leaf_phyllotaxis = "alternate"
leaves_per_shoot = 6
shoot_length = 0.3
shoot_spacing = 0.1
foliage_depth = 2.0
shoot_angle = 50
leaf_angle = 55
shoots_per_tip = 3
shoots_per_spray = 3
leaf_color_jitter = 0.1
autumn_color = [0.55, 0.34, 0.05])toml";
}

// dir/ellipsoid and dir/cone: views.json + 8 perspective 128x128 masks each.
void write_inputs(const std::filesystem::path& dir) {
  const CrownSpec ellipsoid{.shape = "ellipsoid", .height = 9.0, .width = 7.0, .depth = 5.0,
                            .views = 8, .perspective = true};
  const CrownSpec cone{.shape = "cone", .height = 12.0, .width = 5.0, .depth = 5.0,
                       .trunk_height = 1.5, .views = 8, .perspective = true};
  write_view_set(synthesize_view_set(ellipsoid), dir / "ellipsoid");
  write_view_set(synthesize_view_set(cone), dir / "cone");
}

}  // namespace

constinit const MethodEntry kVisualHullMethod{"visual-hull", kKeys, skeleton_pass, builtin_preset,
                                              write_inputs};

}  // namespace forest
