// Method plantons (Wang 2006): organs, distance, learning (k-means, EM, tree max-product),
// synthesis, the expected-size analysis and the model file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "generators/asset/asset_io.h"
#include "generators/core/input_error.h"
#include "generators/core/rng.h"
#include "generators/species/registry.h"
#include "generators/methods/plantons/plantons_learn.h"
#include "generators/methods/plantons/plantons_samples.h"
#include "generators/methods/plantons/plantons_synth.h"

using namespace forest;

namespace {

LearnResult learn_ground_truth(size_t trees, std::array<int, 2> k, double e_max = 16.0) {
  LearnParams p;
  p.initial_plantons = k;
  p.e_max = e_max;
  return learn_plantons(ground_truth_samples(trees, 1), p);
}

std::vector<uint32_t> flatten(const std::vector<std::vector<uint32_t>>& v) {
  std::vector<uint32_t> out;
  for (const auto& s : v) out.insert(out.end(), s.begin(), s.end());
  return out;
}

uint32_t depth_of(const OrganTree& t, size_t k) {
  uint32_t d = 0;
  for (int32_t p = t.organs[k].parent; p >= 0; p = t.organs[size_t(p)].parent) ++d;
  return d;
}

}  // namespace

TEST(Plantons, OrgansHaveParentIndexBelowChild) {
  // A real method's skeleton (L-system) and the ground truth.
  const char* lsystem = R"(method = "lsystem"
seed = 3
iterations = 3
axiom = "X"
step = 0.5
leaf_size = 0.1
shoots_per_tip = 2
[[production]]
predecessor = "X"
successor = "F[+X]F[-X]/X"
)";
  TreeGraph graph;
  GenerateOptions options;
  options.skeleton = &graph;
  generate_from_species_text(lsystem, "l.toml", options);
  ASSERT_GT(graph.nodes.size(), 10u);
  OrganTree tree = organs_from_graph(graph);
  size_t stems = 0, leaves = 0;
  for (size_t k = 0; k < tree.organs.size(); ++k) {
    const Organ& o = tree.organs[k];
    EXPECT_LT(o.parent, int32_t(k));
    EXPECT_EQ(o.parent < 0, k == 0);
    if (o.parent >= 0) {
      EXPECT_EQ(tree.organs[size_t(o.parent)].type, OrganType::Stem);
    }
    EXPECT_GE(o.t, 0.0);
    EXPECT_LE(o.t, 1.0);
    (o.type == OrganType::Stem ? stems : leaves)++;
  }
  EXPECT_EQ(leaves, graph.leaves.size());
  EXPECT_GT(stems, 3u);
  for (const OrganTree& t : ground_truth_samples(2, 5))
    for (size_t k = 0; k < t.organs.size(); ++k) EXPECT_LT(t.organs[k].parent, int32_t(k));
}

TEST(Plantons, OrgansSurviveTheGraphRoundTrip) {
  OrganTree a = ground_truth_samples(1, 9)[0];
  OrganTree b = organs_from_graph(graph_from_organs(a));
  ASSERT_EQ(a.organs.size(), b.organs.size());
  // Synthesis interleaves stems and leaves; extraction lists the stems first. Both list the
  // stems breadth-first with siblings in order of t.
  std::vector<const Organ*> sa, sb;
  for (const Organ& o : a.organs)
    if (o.type == OrganType::Stem) sa.push_back(&o);
  for (const Organ& o : b.organs)
    if (o.type == OrganType::Stem) sb.push_back(&o);
  ASSERT_EQ(sa.size(), sb.size());
  EXPECT_GT(sa.size(), 10u);
  for (size_t k = 0; k < sa.size(); ++k) {
    EXPECT_NEAR(sa[k]->s[0], sb[k]->s[0], 1e-3 * sa[k]->s[0]) << k;
    EXPECT_NEAR(sa[k]->s[1], sb[k]->s[1], 0.01 * sa[k]->s[1]) << k;  // extrapolated to u = 0
    if (k > 0) {
      EXPECT_NEAR(sa[k]->theta, sb[k]->theta, 0.02) << k;
      EXPECT_NEAR(sa[k]->t, sb[k]->t, 0.02) << k;
    }
  }
}

TEST(Plantons, DistanceIsSymmetricZeroOnIdenticalAndNeverAcrossTypes) {
  std::vector<OrganTree> samples = ground_truth_samples(2, 3);
  FeatureScales scales = feature_scales(samples);
  const auto& o = samples[0].organs;
  Rng rng(4);
  for (int i = 0; i < 200; ++i) {
    const Organ& a = o[size_t(rng.uniform() * double(o.size()))];
    const Organ& b = o[size_t(rng.uniform() * double(o.size()))];
    EXPECT_EQ(organ_distance(a, b, scales), organ_distance(b, a, scales));
    EXPECT_EQ(organ_distance(a, a, scales), 0.0);
    if (a.type != b.type) {
      EXPECT_TRUE(std::isinf(organ_distance(a, b, scales)));
    } else {
      EXPECT_TRUE(std::isfinite(organ_distance(a, b, scales)));
    }
  }
  // α = 1/variance: a one-standard-deviation change of the length alone gives D = 1.
  Organ a = o[0], b = o[0];
  b.s[0] += 1.0 / std::sqrt(scales[0].alpha[0]);
  EXPECT_NEAR(organ_distance(a, b, scales), 1.0, 1e-9);
}

TEST(Plantons, TransitionRowsSumToOne) {
  LearnResult r = learn_ground_truth(3, {6, 2});
  const PlantonModel& m = r.model;
  size_t rows = 0;
  for (size_t i = 0; i < m.N(); ++i) {
    double sum = 0.0;
    for (size_t j = 0; j < m.N(); ++j) sum += m.a(i, j).p;
    if (m.plantons[i].child_mean > 0.0) {
      EXPECT_NEAR(sum, 1.0, 1e-12) << "planton " << i;
      ++rows;
    } else {
      EXPECT_EQ(sum, 0.0) << "planton " << i << " has no children but transitions";
    }
    if (m.plantons[i].type == OrganType::Leaf) {
      EXPECT_EQ(m.plantons[i].child_mean, 0.0);
    }
  }
  EXPECT_GE(rows, 3u);
}

TEST(Plantons, TreeMaxProductEqualsBruteForceOnTenOrgans) {
  LearnResult r = learn_ground_truth(2, {4, 2}, 1e6);  // no e_max splits: 6 plantons
  const PlantonModel& m = r.model;
  ASSERT_EQ(m.N(), 6u);
  // Ten organs: a trunk, branches of both kinds and leaves, parameters from the ground truth
  // but mixed up (a branch under a branch, a short "trunk") so that labels are not obvious.
  OrganTree gt = ground_truth_samples(1, 77)[0];
  auto pick = [&](uint32_t truth, size_t nth) {
    for (const Organ& o : gt.organs) {
      bool is = o.type == (truth == 3 ? OrganType::Leaf : OrganType::Stem);
      if (is && nth-- == 0) return o;
    }
    return gt.organs[0];
  };
  OrganTree fx;
  const int32_t parents[10] = {-1, 0, 0, 1, 1, 2, 3, 3, 5, 2};
  const bool leaf[10] = {false, false, false, false, false, false, true, true, true, true};
  for (int k = 0; k < 10; ++k) {
    Organ o = leaf[k] ? pick(3, size_t(k)) : gt.organs[size_t(k == 0 ? 0 : k * 3)];
    o.parent = parents[k];
    fx.organs.push_back(o);
  }
  fx.organs[3].s[0] *= 1.8;  // between P and S
  std::vector<uint32_t> best = relabel_max_product(m, fx);
  // Brute force over every type-consistent labelling.
  std::vector<std::vector<uint32_t>> options(10);
  for (size_t k = 0; k < 10; ++k)
    for (uint32_t i = 0; i < m.N(); ++i)
      if (m.plantons[i].type == fx.organs[k].type) options[k].push_back(i);
  OrganScores u = unary_scores(m, fx);
  std::vector<uint32_t> labels(10), arg;
  double top = -INFINITY;
  size_t visited = 0;
  std::function<void(size_t, double)> rec = [&](size_t k, double score) {
    if (k == 10) {
      ++visited;
      if (score > top) {
        top = score;
        arg = labels;
      }
      return;
    }
    for (uint32_t l : options[k]) {
      labels[k] = l;
      double s = u.unary[k * m.N() + l];
      if (fx.organs[k].parent >= 0) s += pair_score(m, labels[size_t(fx.organs[k].parent)], l, fx.organs[k]);
      rec(k + 1, score + s);
    }
  };
  rec(0, 0.0);
  EXPECT_GT(visited, 1000u);
  EXPECT_EQ(best, arg);
  EXPECT_NEAR(labelling_log_likelihood(m, fx, best), top, 1e-9 * std::abs(top));
}

TEST(Plantons, WellSeparatedDataRecoversTheGroundTruthClusters) {
  std::vector<std::vector<uint32_t>> truth;
  std::vector<OrganTree> samples = ground_truth_samples(4, 1, &truth);
  LearnParams p;
  p.initial_plantons = {3, 1};
  LearnResult r = learn_plantons(samples, p);
  EXPECT_EQ(r.model.N(), 4u);
  EXPECT_TRUE(r.converged);
  EXPECT_DOUBLE_EQ(adjusted_rand_index(flatten(r.labels), flatten(truth)), 1.0);
  // The learned transitions are the ground truth's (T→P = 1, P→S ≈ 0.75, S→L = 1).
  const PlantonModel& m = r.model;
  uint32_t T = r.labels[0][0];
  EXPECT_EQ(m.root_planton, T);
  double child_mean = m.plantons[T].child_mean;
  EXPECT_NEAR(child_mean, 6.0, 0.6);
  // k-means alone from a poor start would not be enough: a bad partition scores lower.
  EXPECT_LT(adjusted_rand_index({0, 0, 1, 1}, {0, 1, 0, 1}), 0.5);
}

TEST(Plantons, FixedSeedGivesTheSameModelAndTree) {
  LearnResult a = learn_ground_truth(2, {5, 2});
  LearnResult b = learn_ground_truth(2, {5, 2});
  EXPECT_EQ(model_to_text(a.model, {}), model_to_text(b.model, {}));
  SynthesisParams sp;
  SynthesizedTree x = synthesize_plantons(a.model, sp, 11), y = synthesize_plantons(a.model, sp, 11),
                  z = synthesize_plantons(a.model, sp, 12);
  ASSERT_EQ(x.tree.organs.size(), y.tree.organs.size());
  for (size_t k = 0; k < x.tree.organs.size(); ++k) {
    EXPECT_EQ(x.tree.organs[k].s, y.tree.organs[k].s);
    EXPECT_EQ(x.tree.organs[k].base, y.tree.organs[k].base);
  }
  bool differs = x.tree.organs.size() != z.tree.organs.size();
  for (size_t k = 0; !differs && k < x.tree.organs.size(); ++k) differs = x.tree.organs[k].base != z.tree.organs[k].base;
  EXPECT_TRUE(differs);
  std::string text = default_species_text("plantons");
  EXPECT_EQ(encode_glb(generate_from_species_text(text, "p.toml")), encode_glb(generate_from_species_text(text, "p.toml")));
}

TEST(Plantons, MeanOrganCountMatchesTheExpectedOffspringEquation) {
  // The ground truth (acyclic: m_T = 1 + 6 (1 + 4 (0.75 · 6 + 0.25)) = 121) and a variant
  // with a cycle S → S, so that m_i = 1 + E[n_i] Σ_j p_ij m_j is a real linear system.
  PlantonModel cyclic = ground_truth_model();
  cyclic.plantons[2].child_mean = 2.2;
  cyclic.plantons[2].child_sd = 0.9;
  cyclic.a(2, 2).p = 0.35;
  cyclic.a(2, 3).p = 0.65;
  cyclic.a(2, 2).count = 1.0;
  cyclic.a(2, 2).azimuth.fill(1.0 / kAzimuthBins);
  cyclic.a(2, 2).theta_mean = 0.6;
  const PlantonModel gt = ground_truth_model();
  for (const PlantonModel* m : {&gt, static_cast<const PlantonModel*>(&cyclic)}) {
    PlantonModel model = *m;
    std::vector<double> expected = expected_organ_counts(model);
    ASSERT_FALSE(expected.empty());
    if (m != &cyclic) EXPECT_NEAR(expected[0], 121.0, 1e-6);
    const int trees = 300;
    double sum = 0.0, sum2 = 0.0;
    SynthesisParams sp;
    sp.max_organs = 1000000;
    sp.max_depth = 1000;
    for (int i = 0; i < trees; ++i) {
      SynthesizedTree s = synthesize_plantons(model, sp, uint64_t(i));
      ASSERT_FALSE(s.capped);
      double n = double(s.tree.organs.size());
      sum += n;
      sum2 += n * n;
    }
    double mean = sum / trees, sd = std::sqrt(std::max(0.0, sum2 / trees - mean * mean));
    EXPECT_NEAR(mean, expected[0], 4.0 * sd / std::sqrt(double(trees)) + 0.5) << "sd " << sd;
  }
}

TEST(Plantons, CapsAreRespected) {
  PlantonModel m = ground_truth_model();
  SynthesisParams sp;
  sp.max_organs = 40;
  SynthesizedTree a = synthesize_plantons(m, sp, 1);
  EXPECT_EQ(a.tree.organs.size(), 40u);
  EXPECT_TRUE(a.capped);
  sp.max_organs = 100000;
  sp.max_depth = 1;
  SynthesizedTree b = synthesize_plantons(m, sp, 1);
  EXPECT_TRUE(b.capped);
  for (size_t k = 0; k < b.tree.organs.size(); ++k) EXPECT_LE(depth_of(b.tree, k), 1u);
  EXPECT_GT(b.tree.organs.size(), 3u);
}

TEST(Plantons, SupercriticalModelsAreDampedAtLearnTimeAndRejectedOnLoad) {
  PlantonModel m = ground_truth_model();
  m.plantons[2].child_mean = 5.0;
  m.a(2, 2).p = 0.5;  // S → S with 5 children: spectral radius 2.5
  m.a(2, 3).p = 0.5;
  m.a(2, 2).count = 1.0;
  m.a(2, 2).azimuth.fill(1.0 / kAzimuthBins);
  EXPECT_GT(spectral_radius(offspring_matrix(m), m.N()), 2.0);
  std::string text = model_to_text(m, {});
  try {
    parse_model(text, "super.json");
    ADD_FAILURE() << "supercritical model accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("spectral radius"), std::string::npos) << e.what();
  }
  double rho = damp_to_subcritical(m, 0.9);
  EXPECT_LE(rho, 0.9);
  EXPECT_GT(rho, 0.85);
  EXPECT_LT(m.damping, 1.0);
  EXPECT_FALSE(expected_organ_counts(m).empty());
}

TEST(Plantons, ModelFileRoundTripsAndBadFilesNameLineAndKey) {
  LearnResult r = learn_ground_truth(2, {4, 1});
  std::string text = model_to_text(r.model, {{"seed", 1}});
  PlantonModel back = parse_model(text, "m.json");
  EXPECT_EQ(model_to_text(back, {{"seed", 1}}), text);
  auto expect_error = [&](const std::string& bad, const std::string& key, int line) {
    try {
      parse_model(bad, "m.json");
      ADD_FAILURE() << "accepted: " << key;
    } catch (const InputError& e) {
      std::string msg = e.what();
      EXPECT_NE(msg.find(key), std::string::npos) << msg;
      if (line > 0) {
        EXPECT_NE(msg.find("m.json:" + std::to_string(line) + ":"), std::string::npos) << msg;
      }
      EXPECT_EQ(msg.find('\n'), std::string::npos);
    }
  };
  expect_error("{\"format\": \"forest-plantons\",\n \"version\": 1,\n oops}", "JSON syntax", 3);
  expect_error(text.substr(0, text.size() / 2), "JSON syntax", 0);
  auto replace = [&](std::string s, const std::string& from, const std::string& to) {
    size_t at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return s.replace(at, from.size(), to);
  };
  // The second planton's line (one planton per line): break its covariance.
  size_t second = text.find("\n    {", text.find("\"plantons\"") + 20);
  int line = 1 + int(std::count(text.begin(), text.begin() + long(second) + 1, '\n'));
  std::string bad = text;
  size_t cov = bad.find("\"covariance\":[", second) + 14;
  bad.replace(cov, 0, "-");
  expect_error(bad, "plantons[1].covariance", line);
  expect_error(replace(text, "\"p\":", "\"p\":0.5,\"q\":"), "transitions", 0);
  expect_error(replace(text, "\"root_planton\"", "\"root_plant\""), "root_planton", 0);
  expect_error(replace(text, "\"type\":\"stem\"", "\"type\":\"flower\""), "plantons[0].type", 0);
  expect_error("[1, 2]", "JSON object", 1);
  EXPECT_THROW(load_model("/nonexistent/model.json"), InputError);
}
