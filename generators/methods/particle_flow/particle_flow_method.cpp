// Species keys of method "particle-flow" (besides the shared image keys of image_species.h):
//   seed; voxels (density grid cells along the longest side, Neubert 2012: 25),
//   carve_threshold (initial density below which voxels are carved); particles (500..2000
//   typical), iterations (200), integrator ("euler" | "heun" | "rk4"), w_base, w_field,
//   w_neighbour (force weights), mass, merge_radius / segment_length (m, 0 = automatic);
//   field_cells (direction field grid, 100), blend (linear h reaches 1 at this fraction of the
//   image diagonal), h_constant (when given: constant h instead of linear).
#include "generators/methods/particle_flow/particle_flow_method.h"

#include "generators/methods/common/image_species.h"
#include "generators/methods/common/image_synthetic.h"
#include "generators/methods/particle_flow/particle_flow_sim.h"

namespace forest {

namespace {

// The method's own species keys; the registry adds the common and the look keys.
constexpr std::string_view kKeys[] = {
    "voxels", "carve_threshold", "particles", "iterations", "integrator", "w_base", "w_field",
    "w_neighbour", "mass", "merge_radius", "segment_length", "field_cells", "blend", "h_constant",
    FOREST_IMAGE_SPECIES_KEYS};

Skeleton skeleton_pass(const TomlTable& t, uint64_t seed) {
  DensitySolveParams dp;
  dp.resolution = int(t.integer("voxels", dp.resolution, 4, 96));
  dp.carve_threshold = t.number("carve_threshold", dp.carve_threshold, 0.0, 1.0);
  FlowParams fp;
  fp.particles = size_t(t.integer("particles", int64_t(fp.particles), 1, 20000));
  fp.iterations = int(t.integer("iterations", fp.iterations, 1, 2000));
  std::string integrator = t.choice("integrator", "rk4", {"euler", "heun", "rk4"});
  fp.integrator = integrator == "euler" ? Integrator::Euler : integrator == "heun" ? Integrator::Heun : Integrator::RK4;
  fp.w_base = t.number("w_base", fp.w_base, 0.0, 100.0);
  fp.w_field = t.number("w_field", fp.w_field, 0.0, 100.0);
  fp.w_neighbour = t.number("w_neighbour", fp.w_neighbour, 0.0, 100.0);
  if (fp.w_base + fp.w_field + fp.w_neighbour <= 0.0) t.fail("w_base", "the force weights must not all be 0");
  fp.mass = t.number("mass", fp.mass, 0.6, 1000.0);  // below ~0.6 the h = 1 step is unstable
  fp.merge_radius = t.number("merge_radius", 0.0, 0.0, 100.0);
  fp.segment_length = t.number("segment_length", 0.0, 0.0, 100.0);
  FieldParams field;
  field.cells = int(t.integer("field_cells", field.cells, 2, 1000));
  field.blend = t.number("blend", field.blend, 1e-4, 10.0);
  if (t.has("h_constant")) {
    field.constant_h = true;
    field.h_constant = t.number("h_constant", 0.0, 1.0);
  }
  const ImageTreeStyle style = read_image_tree_style(
      t, {.tip_radius = 0.008f, .pipe_exponent = 2.3f});
  ViewSet views = read_image_input(t);

  DensitySolution density = solve_density(views, dp);
  if (density.kept_voxels == 0)
    t.fail("carve_threshold", "carves every voxel: the masks do not overlap in the bounds");
  DirectionField3D dir_field = build_direction_field(views, field);
  FlowResult flow = trace_particles(density.grid, dir_field, views.base, fp, seed);
  if (flow.graph.nodes.size() < 2) t.fail(t.has("views") ? "views" : "crown", "no particle could be seeded: the density volume is empty");

  nlohmann::json stats;
  stats["views"] = views.views.size();
  stats["voxels_kept"] = density.kept_voxels;
  stats["lsq_iterations"] = density.iterations;
  stats["lsq_relative_residual"] = density.relative_residual;
  stats["particles"] = flow.seeds.size();
  stats["merges"] = flow.merges;
  stats["trace_joins"] = flow.trace_joins;
  stats["arrived"] = flow.arrived;
  stats["forced_joins"] = flow.forced_joins;
  return finish_image_tree(std::move(flow.graph), style, views, std::move(stats));
}

// Built-in preset: two orthographic 128x128 masks of a synthetic crown, made in memory.
const char* builtin_preset() {
  return R"toml(method = "particle-flow"
# Seed 000 ch3 (Neubert et al. 2007): two orthographic masks at 90 degrees of a synthetic
# ellipsoid crown with projected trunk + first-order branches as attractors, made in memory.
name = "particle_flow_default"
seed = 1
crown = { shape = "ellipsoid", height = 10.0, width = 8.0, trunk_height = 3.0, trunk_radius = 0.35, branches = 5, views = 2, resolution = 128 }
particles = 1000
iterations = 200

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

// dir/oak and dir/poplar: views.json (2 orthographic views at 90 degrees, attractor
// polylines inline) + two 128x128 masks each, and views_svg.json with the same attractors in
// view0_attractors.svg / view1_attractors.svg (pixel coordinates).
void write_inputs(const std::filesystem::path& dir) {
  const CrownSpec oak{.shape = "ellipsoid", .height = 10.0, .width = 9.0, .depth = 7.0,
                      .trunk_height = 3.0, .trunk_radius = 0.4, .branches = 6};
  const CrownSpec poplar{.shape = "ellipsoid", .height = 14.0, .width = 4.0, .depth = 3.5,
                         .trunk_height = 2.0, .trunk_radius = 0.3, .branches = 5};
  write_view_set(synthesize_view_set(oak), dir / "oak", true);
  write_view_set(synthesize_view_set(poplar), dir / "poplar", true);
}

}  // namespace

constinit const MethodEntry kParticleFlowMethod{"particle-flow", kKeys, skeleton_pass,
                                                builtin_preset, write_inputs};

}  // namespace forest
