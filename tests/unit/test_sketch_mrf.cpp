// Method sketch-mrf (Neubert 2012 ch4): segments, factor graph, ICM, EM, templates, propagation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>

#include "generators/asset/asset_io.h"
#include "generators/core/input_error.h"
#include "generators/core/rng.h"
#include "generators/species/registry.h"
#include "generators/methods/sketch_mrf/sketch_mrf_inference.h"
#include "generators/methods/sketch_mrf/sketch_mrf_method.h"
#include "generators/methods/sketch_mrf/sketch_propagation.h"
#include "generators/methods/sketch_mrf/sketch_templates.h"
#include "generators/methods/common/strokes_io.h"

using namespace forest;

namespace {

constexpr double kPi = 3.14159265358979323846;

SketchTree synthetic(const std::string& name, int view = 1, int generations = 3) {
  return sketch_tree_from_drawing(sketch_mrf_synthetic_drawing(name, view, generations));
}

SketchDepths truth(const SketchTree& t) { return {t.true_z, natural_labels(t, t.true_z)}; }

}  // namespace

TEST(SketchMrf, KFactorialLabelHypotheses) {
  size_t factorial = 1;
  for (int K = 1; K <= 6; ++K) {
    factorial *= size_t(K);
    auto h = label_hypotheses(K);
    EXPECT_EQ(h.size(), factorial);
    std::set<std::vector<int>> unique(h.begin(), h.end());
    EXPECT_EQ(unique.size(), factorial);
    for (const auto& p : h) EXPECT_EQ(std::set<int>(p.begin(), p.end()).size(), size_t(K));
  }
  // Lateral gamma means: K = 2 opposite the apical, K > 2 spaced 2 pi / (K - 1).
  EXPECT_DOUBLE_EQ(label_gamma_offset(0, 4), 0.0);
  EXPECT_DOUBLE_EQ(label_gamma_offset(1, 2), kPi);
  for (int K = 3; K <= 6; ++K)
    for (int l = 2; l < K; ++l)
      EXPECT_NEAR(label_gamma_offset(l, K) - label_gamma_offset(l - 1, K), 2 * kPi / (K - 1), 1e-12);
}

TEST(SketchMrf, StrokesBecomeSegments) {
  // A child stroke starting inside a parent segment splits it.
  Drawing d = parse_drawing_json(R"({"strokes": [
    {"id": "t", "points": [[0, 0], [0, 4]]},
    {"id": "b", "parent": "t", "points": [[0.01, 2], [1, 3], [2, 3.5]]},
    {"id": "crown", "role": "crown", "points": [[-3, 1], [3, 1], [0, 6]]}]})", "s.json");
  SketchTree t = sketch_tree_from_drawing(d);
  ASSERT_EQ(t.xy.size(), 5u);  // base, top, split point, 2 branch points
  EXPECT_EQ(t.xy[2], glm::dvec2(0, 2));
  EXPECT_EQ(t.parent[1], 2);  // the top now hangs from the split point
  EXPECT_EQ(t.parent[3], 2);
  EXPECT_EQ(t.children[2].size(), 2u);
  EXPECT_EQ(t.crown.size(), 3u);
  // Errors: a stroke far from its parent, two trunks, a foreign role.
  EXPECT_THROW(sketch_tree_from_drawing(parse_drawing_json(R"({"strokes": [
    {"id": "t", "points": [[0, 0], [0, 4]]}, {"id": "b", "parent": "t", "points": [[3, 2], [4, 3]]}]})", "s.json")),
               InputError);
  EXPECT_THROW(sketch_tree_from_drawing(parse_drawing_json(R"({"strokes": [
    {"id": "t", "points": [[0, 0], [0, 4]]}, {"id": "u", "points": [[1, 0], [1, 4]]}]})", "s.json")),
               InputError);
  EXPECT_THROW(sketch_tree_from_drawing(parse_drawing_json(R"({"strokes": [
    {"id": "t", "role": "axis", "points": [[0, 0], [0, 4]]}]})", "s.json")),
               InputError);
}

TEST(SketchMrf, TrueDepthsScoreHigherThanRandomOnes) {
  for (const char* name : {"broadleaf", "umbrella"}) {
    SketchTree t = synthetic(name);
    ASSERT_FALSE(t.true_z.empty());
    SketchDepths d = truth(t);
    Omega omega = m_step(t, d, Omega{});
    double true_score = log_posterior(t, d, omega);
    Rng rng(5);
    for (int trial = 0; trial < 20; ++trial) {
      SketchDepths r = d;
      for (size_t i = 1; i < r.z.size(); ++i)
        if (t.parent[i] != 0) r.z[i] = rng.uniform(-0.5, 0.5) * t.height;
      EXPECT_GT(true_score, log_posterior(t, r, omega)) << name << " trial " << trial;
    }
  }
}

TEST(SketchMrf, IcmNeverDecreasesLogP) {
  SketchTree t = synthetic("broadleaf");
  Omega omega = sketch_template_database()[size_t(find_sketch_template("fig2_1"))].omega;
  SketchDepths d = infer_bottom_up(t, omega);
  InferenceParams p;
  double start = log_p_icm(t, d, omega, p.k_e);
  std::vector<double> log_p;
  refine_icm(t, d, omega, p, &log_p);
  ASSERT_GE(log_p.size(), 2u);
  EXPECT_GE(log_p[0], start - 1e-9 * std::abs(start));
  for (size_t k = 1; k < log_p.size(); ++k) EXPECT_GE(log_p[k], log_p[k - 1] - 1e-9 * std::abs(log_p[k]));
  EXPECT_GT(log_p.back(), start);  // and it does improve on the bottom-up solution
}

TEST(SketchMrf, MStepIsSampleStatistics) {
  SketchTree t = synthetic("broadleaf");
  SketchDepths d = truth(t);
  Omega o = m_step(t, d, Omega{});
  auto a = segment_angles(t, d.z);
  double s = 0, s2 = 0, al = 0, al2 = 0;
  int n = 0, na = 0;
  for (size_t c = 1; c < t.xy.size(); ++c) {
    if (t.parent[c] <= 0) continue;
    s += a[c].s, s2 += a[c].s * a[c].s, ++n;
    if (d.label[c] == 0) al += a[c].angle, al2 += a[c].angle * a[c].angle, ++na;
  }
  ASSERT_GT(n, 5);
  ASSERT_GT(na, 2);
  EXPECT_NEAR(o.mu_s, s / n, 1e-12);
  EXPECT_NEAR(o.sd_s, std::sqrt(s2 / n - (s / n) * (s / n)), 1e-9);
  EXPECT_NEAR(o.mu_a, al / na, 1e-12);
  EXPECT_NEAR(o.sd_a, std::sqrt(al2 / na - (al / na) * (al / na)), 1e-9);
}

TEST(SketchMrf, ResultKeepsTheSketchAndTheRoot) {
  SketchTree t = synthetic("broadleaf");
  InferenceResult r = infer_depths(t, sketch_template_database()[0].omega, {});
  EXPECT_GE(r.em_iterations, 1);
  EXPECT_LE(r.em_iterations, 8);
  EXPECT_EQ(r.depths.z[0], 0.0);
  for (size_t i = 1; i < t.xy.size(); ++i)
    if (t.parent[i] == 0) EXPECT_EQ(r.depths.z[i], 0.0);
  CrownSurface crown{t.crown, t.xy[0].x};
  PropagatedTree g = propagate_branches(t, r.depths, &crown, {}, 3);
  // Sketched nodes come first with x, y exactly as drawn.
  std::multiset<std::pair<double, double>> drawn, kept;
  for (glm::dvec2 p : t.xy) drawn.insert({p.x, p.y});
  size_t sketched = 0;
  for (size_t i = 0; i < g.position.size(); ++i)
    if (g.sketched[i]) kept.insert({g.position[i].x, g.position[i].y}), ++sketched;
  EXPECT_EQ(drawn, kept);
  EXPECT_GT(g.position.size(), sketched);  // propagation added branches ...
  for (size_t i = 0; i < g.position.size(); ++i) {
    EXPECT_LT(g.parent[i], int(i));
    if (!g.sketched[i]) EXPECT_TRUE(crown.contains(g.position[i])) << i;  // ... inside the crown
  }
}

TEST(SketchMrf, SelectsTheTemplateTheSketchCameFrom) {
  const auto& db = sketch_template_database();
  ASSERT_GE(db.size(), 3u);
  for (size_t i = 0; i < db.size(); ++i)
    for (int view : {1, 3}) {
      SketchTree t = sketch_tree_from_drawing(project_template(db[i], view, 3, true));
      TemplateChoice c = choose_template(t);
      EXPECT_EQ(c.index, int(i)) << db[i].name << " view " << view << " picked " << db[size_t(c.index)].name;
    }
}

TEST(SketchMrf, GeneratesDeterministically) {
  std::string text = default_species_text("sketch-mrf");
  auto bytes = [&](uint64_t seed) { return encode_glb(generate_from_species_text(text, "sk.toml", {seed})); };
  EXPECT_EQ(bytes(3), bytes(3));
  EXPECT_NE(bytes(3), bytes(4));
  TreeModel m = generate_from_species_text(text, "sk.toml");
  EXPECT_GT(m.leaves.size(), 100u);
  EXPECT_EQ(m.meta["method"], "sketch-mrf");
  EXPECT_EQ(m.meta["sketch_mrf"]["template"], "broadleaf");
}

TEST(SketchMrf, SpeciesErrors) {
  auto fails_on = [](const std::string& extra, const std::string& key) {
    try {
      generate_from_species_text("method = \"sketch-mrf\"\n" + extra + "\n", "sk.toml");
      ADD_FAILURE() << extra;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("sk.toml:2"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  fails_on("strokes = \"no/such/file.json\"", "strokes");
  fails_on("template = \"baobab\"", "template");
  fails_on("em_iterations = 0", "em_iterations");
  fails_on("interaction = nan", "interaction");
  fails_on("generations = 99", "generations");
}

TEST(SketchMrf, PresetsReadCommittedInputs) {
  auto dir = std::filesystem::path(FOREST_SOURCE_DIR) / "scenes" / "species";
  for (const char* name : {"sketch_mrf_maple", "sketch_mrf_pine"}) {
    TreeModel m = generate_from_species(dir / (std::string(name) + ".toml"));
    EXPECT_GT(m.branches.indices.size(), 0u) << name;
    EXPECT_GT(m.leaves.size(), 0u) << name;
  }
}

TEST(SketchMrf, SvgAndJsonOfTheSameStrokesGiveTheSameTree) {
  // The same polylines (at the 4 decimals SVG keeps) as JSON and as SVG.
  Drawing d = read_drawing(std::filesystem::path(FOREST_SOURCE_DIR) / "scenes/inputs/sketch-mrf/maple.json");
  for (Stroke& s : d.strokes) {
    for (glm::dvec2& p : s.points) p = glm::round(p * 1e4) / 1e4;
    s.depth.clear();
  }
  auto dir = std::filesystem::temp_directory_path() / ("forest_sk_svg_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "s.json") << drawing_to_json(d);
  std::ofstream(dir / "s.svg") << drawing_to_svg(d);
  auto tree = [&](const char* file) {
    return generate_from_species_text("method = \"sketch-mrf\"\nstrokes = \"" + (dir / file).string() +
                                          "\"\ngenerations = 0\nem_iterations = 2\n",
                                      "sk.toml");
  };
  TreeModel a = tree("s.json"), b = tree("s.svg");
  ASSERT_GT(a.branches.vertices.size(), 0u);
  ASSERT_EQ(a.branches.vertices.size(), b.branches.vertices.size());
  EXPECT_EQ(0, std::memcmp(a.branches.vertices.data(), b.branches.vertices.data(),
                           a.branches.vertices.size() * sizeof(a.branches.vertices[0])));
  EXPECT_EQ(a.branches.indices, b.branches.indices);
  EXPECT_EQ(a.leaves.size(), b.leaves.size());
  std::filesystem::remove_all(dir);
}
