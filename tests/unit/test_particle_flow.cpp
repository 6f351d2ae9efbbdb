// Particle flow (Neubert 2012 ch3): density volume by least squares, seeding, direction field,
// integrators, particle tracing into one rooted tree, determinism and bad inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "generators/core/input_error.h"
#include "generators/core/rng.h"
#include "generators/methods/common/image_synthetic.h"
#include "generators/methods/common/image_tree_util.h"
#include "generators/species/registry.h"
#include "generators/methods/particle_flow/particle_flow_sim.h"

using namespace forest;
namespace fs = std::filesystem;

namespace {

ViewSet small_views(int resolution) {
  CrownSpec s;
  s.resolution = resolution;
  s.branches = 4;
  return synthesize_view_set(s);
}

}  // namespace

TEST(ParticleFlow, ProjectionMatrixIsZeroOneWithAPixelPerRow) {
  ViewSet set = small_views(32);
  DensityGrid g = make_density_grid(set.bounds, 8);
  std::vector<size_t> all(g.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = i;
  auto a = projection_matrix(g, set, all);
  EXPECT_EQ(a.rows(), Eigen::Index(2 * 32 * 32));
  EXPECT_EQ(a.cols(), Eigen::Index(g.size()));
  size_t ones = 0;
  for (int k = 0; k < a.outerSize(); ++k)
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(a, k); it; ++it) {
      EXPECT_EQ(it.value(), 1.0);
      ++ones;
    }
  EXPECT_GT(ones, size_t(a.rows()));
  // An orthographic front pixel ray through the grid crosses exactly the voxels of one
  // column along z: dims.z entries (the front camera looks along -Z).
  const int centre_row = 16 * 32 + 16;
  EXPECT_EQ(a.row(centre_row).nonZeros(), g.dims.z);
}

TEST(ParticleFlow, LeastSquaresRecoversASyntheticVolume) {
  ViewSet set = small_views(48);
  DensityGrid g = make_density_grid(set.bounds, 10);
  std::vector<size_t> all(g.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = i;
  auto a = projection_matrix(g, set, all);
  // A smooth blob of optical depth; b = A x exactly (the images such a volume would make).
  Eigen::VectorXd x(Eigen::Index(g.size()));
  for (size_t i = 0; i < g.size(); ++i) {
    glm::dvec3 c = g.corner(g.cell_of_index(i)) + 0.5 * g.cell - 0.5 * (set.bounds.min + set.bounds.max);
    x[Eigen::Index(i)] = 0.4 * std::exp(-glm::dot(c, c) / 8.0);
  }
  Eigen::VectorXd b = a * x;
  int iterations = 0;
  Eigen::VectorXd solved = least_squares(a, b, 2000, 1e-12, &iterations);
  EXPECT_LT((a * solved - b).norm() / b.norm(), 1e-4);
  // And on the synthetic masks the pipeline's residual is reported and finite.
  DensitySolution s = solve_density(small_views(64), DensitySolveParams{});
  EXPECT_GT(s.kept_voxels, 100u);
  EXPECT_LT(s.kept_voxels, s.grid.size());
  EXPECT_TRUE(std::isfinite(s.relative_residual));
  for (double v : s.grid.alpha) EXPECT_TRUE(v >= 0.0 && v < 1.0);
}

TEST(ParticleFlow, SeedingIsProportionalToDensity) {
  DensityGrid g = make_density_grid({{0, 0, 0}, {4, 4, 4}}, 4);
  Rng rng(5, 0);
  for (double& a : g.alpha) a = rng.uniform() < 0.3 ? 0.0 : rng.uniform(0.05, 0.95);
  const size_t n = 64000;
  auto seeds = seed_particles(g, n, 11);
  ASSERT_EQ(seeds.size(), n);
  std::vector<double> counts(g.size(), 0.0);
  for (glm::dvec3 p : seeds) {
    glm::ivec3 c = glm::ivec3(glm::floor((p - g.origin) / g.cell));
    counts[g.index(c.x, c.y, c.z)] += 1.0;
  }
  double total = 0.0;
  for (double a : g.alpha) total += a;
  double chi2 = 0.0;
  int df = -1;
  for (size_t i = 0; i < g.size(); ++i) {
    if (g.alpha[i] == 0.0) {
      EXPECT_EQ(counts[i], 0.0);  // never in an empty voxel
      continue;
    }
    double expected = n * g.alpha[i] / total;
    chi2 += (counts[i] - expected) * (counts[i] - expected) / expected;
    ++df;
  }
  // chi^2 with df degrees of freedom: mean df, sd sqrt(2 df); 5 sd is far in the tail.
  EXPECT_LT(chi2, df + 5.0 * std::sqrt(2.0 * df)) << "df " << df;
}

TEST(ParticleFlow, DirectionFieldFollowsEquation37AndIsBounded) {
  std::vector<Polyline2> lines = {{{50, 90}, {50, 10}}};  // root end (bottom) first
  FieldParams p;
  // On the graph: the tangent toward the root (+v, down the image).
  glm::dvec2 on = field_value(lines, {50, 40}, 10.0, p);
  EXPECT_NEAR(on.x, 0.0, 1e-12);
  EXPECT_NEAR(on.y, 1.0, 1e-12);
  // Far away (d >= blend): straight toward the closest point.
  glm::dvec2 far = field_value(lines, {80, 40}, 10.0, p);
  EXPECT_NEAR(far.x, -1.0, 1e-12);
  EXPECT_NEAR(far.y, 0.0, 1e-12);
  // Halfway (linear h = 0.5): the mean of both unit vectors.
  glm::dvec2 mid = field_value(lines, {55, 40}, 10.0, p);
  EXPECT_NEAR(mid.x, -0.5, 1e-12);
  EXPECT_NEAR(mid.y, 0.5, 1e-12);
  // 3D field of two views: |f| <= 1 everywhere.
  ViewSet set = small_views(64);
  DirectionField3D f3 = build_direction_field(set, p);
  ASSERT_FALSE(f3.empty());
  Rng rng(3, 0);
  double largest = 0.0;
  for (int k = 0; k < 5000; ++k) {
    glm::dvec3 x = set.bounds.min + glm::dvec3(rng.uniform(), rng.uniform(), rng.uniform()) * set.bounds.size();
    largest = std::max(largest, glm::length(f3.at(x)));
  }
  EXPECT_LE(largest, 1.0 + 1e-12);
  EXPECT_GT(largest, 0.5);
}

TEST(ParticleFlow, IntegratorOrders) {
  // y' = y cos t, y(0) = 1: y(t) = exp(sin t). Error ratio when halving h is 2^order.
  auto f = [](double t, double y) { return y * std::cos(t); };
  auto error = [&](auto step, double h) {
    double y = 1.0;
    int n = int(std::lround(2.0 / h));
    for (int i = 0; i < n; ++i) y = step(y, i * h, h, f);
    return std::abs(y - std::exp(std::sin(2.0)));
  };
  auto rk4 = [](double y, double t, double h, auto&& fn) { return rk4_step(y, t, h, fn); };
  auto heun = [](double y, double t, double h, auto&& fn) { return heun_step(y, t, h, fn); };
  auto euler = [](double y, double t, double h, auto&& fn) { return euler_step(y, t, h, fn); };
  double r4 = error(rk4, 0.1) / error(rk4, 0.05);
  double r2 = error(heun, 0.1) / error(heun, 0.05);
  double r1 = error(euler, 0.1) / error(euler, 0.05);
  EXPECT_NEAR(r4, 16.0, 2.0);
  EXPECT_NEAR(r2, 4.0, 0.6);
  EXPECT_NEAR(r1, 2.0, 0.3);
}

TEST(ParticleFlow, ParticlesMergeAndAllReachTheRoot) {
  ViewSet set = small_views(128);
  DensitySolution d = solve_density(set, DensitySolveParams{});
  DirectionField3D field = build_direction_field(set, FieldParams{});
  FlowParams fp;
  fp.particles = 600;
  FlowResult r = trace_particles(d.grid, field, set.base, fp, 4);
  ASSERT_EQ(r.seeds.size(), 600u);
  EXPECT_TRUE(is_rooted_tree(r.graph));
  // Each particle ends exactly once: merged into another, joined a trace, arrived, or was
  // joined at the end.
  EXPECT_EQ(r.merges + r.trace_joins + r.arrived + r.forced_joins, 600u);
  EXPECT_GT(r.merges + r.trace_joins, 500u);  // streams form branches
  EXPECT_LE(r.arrived, 10u);                  // and one trunk, not a bush of stems
  EXPECT_LE(r.forced_joins, 600u / 20u);     // and they flow to the base by themselves
  // Active particles never increase.
  for (size_t k = 1; k < r.active.size(); ++k) EXPECT_LE(r.active[k], r.active[k - 1]);
  EXPECT_EQ(r.active.front(), 600u);
  // Every seed is a tip of the tree, and every tip reaches node 0 through its parents.
  auto children = children_of(r.graph);
  size_t tips = 0;
  for (size_t i = 0; i < r.graph.nodes.size(); ++i) tips += children[i].empty();
  EXPECT_LE(tips, 600u);
  EXPECT_GT(tips, 100u);
  EXPECT_NEAR(glm::length(glm::dvec3(r.graph.nodes[0].position) - set.base), 0.0, 1e-6);
}

TEST(ParticleFlow, DefaultPresetIsDeterministic) {
  std::string text = default_species_text("particle-flow");
  TreeModel a = generate_from_species_text(text, "pf.toml");
  TreeModel b = generate_from_species_text(text, "pf.toml");
  ASSERT_GT(a.branches.vertices.size(), 0u);
  EXPECT_GT(a.leaves.size(), 100u);
  EXPECT_EQ(a.meta.dump(), b.meta.dump());
  ASSERT_EQ(a.branches.vertices.size(), b.branches.vertices.size());
  EXPECT_EQ(0, std::memcmp(a.branches.vertices.data(), b.branches.vertices.data(),
                           a.branches.vertices.size() * sizeof(a.branches.vertices[0])));
  GenerateOptions other;
  other.seed = 42;
  TreeModel c = generate_from_species_text(text, "pf.toml", other);
  EXPECT_NE(c.meta["node_count"], a.meta["node_count"]);
}

TEST(ParticleFlow, BadInputsNameFileAndKey) {
  fs::path d = fs::temp_directory_path() / ("forest_pf_bad_" + std::to_string(::getpid()));
  fs::create_directories(d);
  auto expect = [&](const std::string& body, const std::string& line_key) {
    std::ofstream(d / "s.toml") << "method = \"particle-flow\"\n" << body;
    try {
      generate_from_species(d / "s.toml");
      ADD_FAILURE() << body;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(line_key), std::string::npos) << e.what();
    }
  };
  expect("views = \"missing.json\"\n", "s.toml:2: views");
  expect("crown = { shape = \"ellipsoid\" }\nviews = \"a.json\"\n", "s.toml");
  expect("crown = { shape = \"ellipsoid\" }\nparticles = 0\n", "s.toml:3: particles");
  expect("crown = { shape = \"ellipsoid\" }\nintegrator = \"verlet\"\n", "s.toml:3: integrator");
  expect("crown = { shape = \"ellipsoid\", height = nan }\n", "crown.height");
  fs::remove_all(d);
}

TEST(ParticleFlow, SvgAttractorsGiveTheSameTreeAsJson) {
  // write_view_set writes the attractors inline (views.json) and as one SVG per view
  // (views_svg.json): the two files must give the same tree, bit for bit.
  fs::path d = fs::temp_directory_path() / ("forest_pf_svg_" + std::to_string(::getpid()));
  write_view_set(small_views(64), d, true);
  ASSERT_TRUE(fs::exists(d / "view0_attractors.svg"));
  ViewSet json = load_view_set(d / "views.json"), svg = load_view_set(d / "views_svg.json");
  ASSERT_EQ(json.views.size(), svg.views.size());
  for (size_t v = 0; v < json.views.size(); ++v) {
    ASSERT_FALSE(json.views[v].attractors.empty());
    EXPECT_EQ(json.views[v].attractors, svg.views[v].attractors) << "view " << v;
  }
  auto tree = [&](const std::string& views) {
    return generate_from_species_text("method = \"particle-flow\"\nviews = \"" + (d / views).string() +
                                          "\"\nparticles = 150\niterations = 60\nvoxels = 12\n",
                                      "pf.toml");
  };
  TreeModel a = tree("views.json"), b = tree("views_svg.json");
  ASSERT_GT(a.branches.vertices.size(), 0u);
  ASSERT_EQ(a.branches.vertices.size(), b.branches.vertices.size());
  EXPECT_EQ(0, std::memcmp(a.branches.vertices.data(), b.branches.vertices.data(),
                           a.branches.vertices.size() * sizeof(a.branches.vertices[0])));
  EXPECT_EQ(a.branches.indices, b.branches.indices);
  // A broken SVG names the SVG file and its line.
  std::ofstream(d / "view0_attractors.svg") << "<svg>\n<path d=\"M 0 0 Q 1 1 2 2\"/>\n</svg>\n";
  try {
    load_view_set(d / "views_svg.json");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("view0_attractors.svg:2"), std::string::npos) << e.what();
  }
  fs::remove_all(d);
}
