// Baked assets: hull mesh, hull samples, the priority order of the leaves and the PR tables
// survive the .glb round trip element by element; malformed tables fail.
//
// Every array that travels holds distinct, position-dependent, non-monotonic values, so an
// index, order, stride or off-by-one bug in the writer or the reader (a reversed, shifted,
// truncated or constant array) cannot round-trip unnoticed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <numeric>
#include <string>

#include "generators/asset/asset_io.h"
#include "generators/asset/pr_tables.h"
#include "generators/bake/hull/hull.h"
#include "generators/bake/priority/priority.h"
#include "generators/core/input_error.h"
#include "generators/species/registry.h"

using namespace forest;

namespace {

// n values in [lo, hi], all distinct, neither increasing nor decreasing: lo + (hi - lo) *
// frac(salt + i φ) (the golden-ratio sequence never repeats and keeps jumping back).
std::vector<float> distinct_values(size_t n, float lo, float hi, double salt) {
  std::vector<float> v(n);
  for (size_t i = 0; i < n; ++i) {
    double t = salt + double(i) * 0.6180339887498949;
    t -= std::floor(t);
    v[i] = float(double(lo) + double(hi - lo) * t);
  }
  return v;
}

bool all_distinct(std::vector<float> v) {
  std::sort(v.begin(), v.end());
  return std::adjacent_find(v.begin(), v.end()) == v.end();
}

bool monotonic(const std::vector<float>& v) {
  return std::is_sorted(v.begin(), v.end()) || std::is_sorted(v.rbegin(), v.rend());
}

// The JSON chunk of a .glb.
nlohmann::json glb_json(const std::vector<uint8_t>& glb) {
  uint32_t len;
  std::memcpy(&len, glb.data() + 12, 4);
  return nlohmann::json::parse(glb.begin() + 20, glb.begin() + 20 + len);
}

// The .glb with its extras.forest changed by `edit` (the JSON chunk rewritten, the BIN chunk
// kept): how a tampered or hand-edited asset looks to the reader.
std::vector<uint8_t> with_forest_extras(const std::vector<uint8_t>& glb, const std::function<void(nlohmann::json&)>& edit) {
  uint32_t len;
  std::memcpy(&len, glb.data() + 12, 4);
  nlohmann::json j = glb_json(glb);
  edit(j["extras"]["forest"]);
  std::string text = j.dump();
  while (text.size() % 4) text.push_back(' ');
  const size_t bin_at = 20 + size_t(len), bin_size = glb.size() - bin_at;  // the BIN chunk
  std::vector<uint8_t> out(20 + text.size() + bin_size);
  std::memcpy(out.data(), glb.data(), 20);
  std::memcpy(out.data() + 20, text.data(), text.size());
  std::memcpy(out.data() + 20 + text.size(), glb.data() + bin_at, bin_size);
  uint32_t total = uint32_t(out.size()), text_len = uint32_t(text.size());
  std::memcpy(out.data() + 8, &total, 4);
  std::memcpy(out.data() + 12, &text_len, 4);
  return out;
}

std::string str(glm::vec3 v) {
  return "(" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) + ")";
}

void expect_same_floats(const std::vector<float>& got, const std::vector<float>& want, const char* key) {
  ASSERT_EQ(got.size(), want.size()) << key;
  for (size_t i = 0; i < want.size(); ++i) EXPECT_EQ(got[i], want[i]) << key << "[" << i << "]";
}

}  // namespace

TEST(BakeIo, HullAndTablesRoundTrip) {
  TreeModel m = generate_from_species(std::string(FOREST_SOURCE_DIR) + "/scenes/species/conifer.toml");
  ASSERT_GE(m.leaves.size(), 10u);
  // Per-leaf colors that identify each leaf (and travel with it when the order changes).
  for (size_t i = 0; i < m.leaves.size(); ++i) {
    double t = 0.25 + double(i) * 0.6180339887498949;
    m.leaves[i].color = glm::vec3(float(t - std::floor(t)), float(i % 7) / 7.0f, 1.0f - float(i % 5) / 5.0f);
  }
  Hull h = build_hull(m.leaves, plant_height(m));
  ASSERT_FALSE(h.mesh.indices.empty());
  ASSERT_GE(h.samples.size(), 8u);
  ASSERT_EQ(h.sample_normals.size(), h.samples.size());

  // The priority order: a real bake order, which must be a non-trivial permutation.
  const std::vector<LeafPlacement> unordered = m.leaves;
  const std::vector<uint32_t> order = priority_order(m, h, Priority::combined, 7);
  ASSERT_EQ(order.size(), unordered.size());
  {
    std::vector<uint32_t> sorted = order, identity(order.size());
    std::sort(sorted.begin(), sorted.end());
    std::iota(identity.begin(), identity.end(), 0u);
    ASSERT_EQ(sorted, identity) << "not a permutation";
    ASSERT_NE(order, identity) << "the identity order would not show a reordering bug";
    std::vector<uint32_t> reversed(identity.rbegin(), identity.rend());
    ASSERT_NE(order, reversed);
  }
  reorder_leaves(m, order);
  m.bake.priority = std::string(priority_name(Priority::combined));

  attach_hull(m, h);
  ASSERT_FALSE(m.hull.indices.empty());
  // The hull carries distinct texture coordinates too (marching cubes leaves them all zero).
  for (size_t i = 0; i < m.hull.vertices.size(); ++i) {
    double t = 0.1 + double(i) * 0.6180339887498949;
    m.hull.vertices[i].uv = glm::vec2(float(t - std::floor(t)), float(i % 1000) / 1000.0f);
  }

  // Tables of every size, each array distinct from the others.
  PrTables t;
  t.size0 = 317.5f;
  for (uint32_t b = 0; b < PR_SIZES; ++b) {
    PrSizeTables st;
    st.s_opt = distinct_values(S_SAMPLES, 0.5f, 40.0f, 0.23 + 0.01 * b);
    st.q_opt = distinct_values(S_SAMPLES, -1.0f, 1.0f, 0.37 + 0.01 * b);
    st.q_inverse = distinct_values(S_SAMPLES, -0.9f, 0.95f, 0.41 + 0.01 * b);
    st.lambda_opt = distinct_values(D_SAMPLES, 0.05f, 0.95f, 0.67 + 0.01 * b);
    st.s_far = distinct_values(F_SAMPLES, 20.0f, 200.0f, 0.71 + 0.01 * b);
    st.q_far = distinct_values(F_SAMPLES, -1.0f, 1.0f, 0.53 + 0.01 * b);
    st.q_inverse_far = distinct_values(F_SAMPLES, -0.9f, 0.95f, 0.59 + 0.01 * b);
    st.q_low = distinct_values(S_SAMPLES, -0.5f, 0.9f, 0.61 + 0.01 * b);
    st.q_low_far = distinct_values(F_SAMPLES, -0.5f, 0.9f, 0.83 + 0.01 * b);
    for (const auto* v : {&st.s_opt, &st.q_opt, &st.q_inverse, &st.lambda_opt}) {
      ASSERT_TRUE(all_distinct(*v));
      ASSERT_FALSE(monotonic(*v));
    }
    t.sizes.push_back(st);
  }
  t.priority = "combined";
  t.views = 13;
  t.resolution = 321;
  m.bake.pr_tables = t;
  // The PR diagram: distinct points (λ, s, size, P, R), P and R as doubles.
  {
    std::vector<float> l = distinct_values(37, 0.0f, 1.0f, 0.13), sc = distinct_values(37, 0.5f, 90.0f, 0.29),
                       px = distinct_values(37, 4.0f, 600.0f, 0.31);
    for (size_t k = 0; k < l.size(); ++k)
      m.bake.pr_samples.push_back({l[k], sc[k], px[k], 0.3 + 0.7 / double(k + 2), 1.0 / std::sqrt(double(k + 1))});
  }

  std::vector<uint8_t> bytes = encode_glb(m);
  TreeModel back = decode_glb(bytes, "x.glb");

  // Hull mesh: every vertex attribute and every index, in order.
  EXPECT_EQ(back.hull.indices, m.hull.indices);
  ASSERT_EQ(back.hull.vertices.size(), m.hull.vertices.size());
  for (size_t i = 0; i < m.hull.vertices.size(); ++i) {
    const Vertex &a = back.hull.vertices[i], &b = m.hull.vertices[i];
    ASSERT_EQ(a.position, b.position) << "hull vertex " << i << ": " << str(a.position) << " != " << str(b.position);
    ASSERT_LT(glm::distance(a.normal, glm::normalize(b.normal)), 1e-6f) << "hull normal " << i;
    ASSERT_EQ(a.uv, b.uv) << "hull uv " << i;
  }

  // Hull samples and their normals: the baked points, one by one, in the baked order.
  ASSERT_TRUE(back.bake.hull.has_value());
  ASSERT_EQ(back.bake.hull->points.size(), h.samples.size());
  ASSERT_EQ(back.bake.hull->normals.size(), h.sample_normals.size());
  for (size_t k = 0; k < h.samples.size(); ++k) {
    EXPECT_EQ(back.bake.hull->points[k], h.samples[k]) << "hull_samples[" << k << "]";
    EXPECT_EQ(back.bake.hull->normals[k], h.sample_normals[k]) << "hull_sample_normals[" << k << "]";
  }
  EXPECT_EQ(back.bake.hull->iso, h.iso);
  EXPECT_EQ(back.bake.hull->radius, h.radius);
  // The bake keys live in TreeModel::bake, not in meta.
  for (const char* key : kBakeKeys) EXPECT_FALSE(back.meta.contains(key)) << key;

  // Priority order: the k-th leaf read back is the leaf order[k] of the unordered model.
  EXPECT_EQ(back.bake.priority, "combined");
  ASSERT_EQ(back.leaves.size(), unordered.size());
  for (size_t k = 0; k < order.size(); ++k) {
    const LeafPlacement &a = back.leaves[k], &b = unordered[order[k]];
    ASSERT_EQ(a.position, b.position) << "leaf " << k << " (was leaf " << order[k] << "): " << str(a.position)
                                      << " != " << str(b.position);
    ASSERT_EQ(a.color, b.color) << "leaf " << k;
    ASSERT_NEAR(a.scale, b.scale, 1e-6f * b.scale) << "leaf " << k;
    glm::quat qa = a.rotation, qb = glm::normalize(b.rotation);
    ASSERT_GT(std::abs(glm::dot(qa, qb)), 1.0f - 1e-6f) << "leaf " << k;
  }

  // PR tables: every array, element by element, and the scalars.
  const std::optional<PrTables>& tables = back.bake.pr_tables;
  ASSERT_TRUE(tables.has_value());
  EXPECT_TRUE(back.bake.baked());
  ASSERT_EQ(tables->sizes.size(), size_t(PR_SIZES));
  EXPECT_EQ(tables->size0, 317.5f);
  for (uint32_t b = 0; b < PR_SIZES; ++b) {
    SCOPED_TRACE("size " + std::to_string(b));
    expect_same_floats(tables->sizes[b].s_opt, t.sizes[b].s_opt, "s_opt");
    expect_same_floats(tables->sizes[b].q_opt, t.sizes[b].q_opt, "q_opt");
    expect_same_floats(tables->sizes[b].q_inverse, t.sizes[b].q_inverse, "q_inverse");
    expect_same_floats(tables->sizes[b].lambda_opt, t.sizes[b].lambda_opt, "lambda_opt");
    expect_same_floats(tables->sizes[b].s_far, t.sizes[b].s_far, "s_far");
    expect_same_floats(tables->sizes[b].q_far, t.sizes[b].q_far, "q_far");
    expect_same_floats(tables->sizes[b].q_inverse_far, t.sizes[b].q_inverse_far, "q_inverse_far");
    expect_same_floats(tables->sizes[b].q_low, t.sizes[b].q_low, "q_low");
    expect_same_floats(tables->sizes[b].q_low_far, t.sizes[b].q_low_far, "q_low_far");
  }
  EXPECT_EQ(tables->priority, "combined");
  EXPECT_EQ(tables->views, 13);
  EXPECT_EQ(tables->resolution, 321);

  // PR samples: every point, in order, P and R as the doubles they were.
  ASSERT_EQ(back.bake.pr_samples.size(), m.bake.pr_samples.size());
  for (size_t k = 0; k < m.bake.pr_samples.size(); ++k) {
    const PrPoint &a = back.bake.pr_samples[k], &b = m.bake.pr_samples[k];
    EXPECT_EQ(a.lambda, b.lambda) << "pr_samples[" << k << "]";
    EXPECT_EQ(a.scale, b.scale) << "pr_samples[" << k << "]";
    EXPECT_EQ(a.size, b.size) << "pr_samples[" << k << "]";
    EXPECT_EQ(a.precision, b.precision) << "pr_samples[" << k << "]";
    EXPECT_EQ(a.recall, b.recall) << "pr_samples[" << k << "]";
  }

  // The same tables straight from JSON (no .glb in between) also come back unchanged.
  PrTables direct = pr_tables_from_json(to_json(t), "y.glb");
  expect_same_floats(direct.sizes[3].s_opt, t.sizes[3].s_opt, "s_opt (json)");
  expect_same_floats(direct.sizes[5].lambda_opt, t.sizes[5].lambda_opt, "lambda_opt (json)");

  // What was read back writes the same extras.forest: nothing lost, nothing reordered.
  EXPECT_EQ(glb_json(encode_glb(back))["extras"]["forest"].dump(), glb_json(bytes)["extras"]["forest"].dump());
}

TEST(BakeIo, MalformedTablesNameTheKey) {
  nlohmann::json tables = {{"format", kPrTablesFormat}, {"lambda", {0.1, 0.2}}};
  try {
    pr_tables_from_json(tables, "m.glb");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("m.glb"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("pr_tables.lambda"), std::string::npos);
  }
}

namespace {

// A small baked model: hull, combined order, tables and PR samples that pass the checks.
const std::vector<uint8_t>& baked_glb() {
  static const std::vector<uint8_t> bytes = [] {
    TreeModel m = generate_from_species(std::string(FOREST_SOURCE_DIR) + "/scenes/species/conifer.toml");
    Hull h = build_hull(m.leaves, plant_height(m));
    attach_hull(m, h);
    apply_priority(m, h, Priority::combined, 3);
    PrSizeTables st;
    st.s_opt.assign(S_SAMPLES, 1.5f);
    st.q_opt.assign(S_SAMPLES, 0.5f);
    st.q_inverse.assign(S_SAMPLES, 0.25f);
    st.lambda_opt.assign(D_SAMPLES, 0.75f);
    st.s_far.assign(F_SAMPLES, 30.0f);
    st.q_far.assign(F_SAMPLES, 0.1f);
    st.q_inverse_far.assign(F_SAMPLES, 0.05f);
    st.q_low.assign(S_SAMPLES, 0.4f);
    st.q_low_far.assign(F_SAMPLES, 0.02f);
    PrTables t = pr_tables_at_every_size(st, 64.0f);
    t.priority = "combined";
    t.views = 2;
    t.resolution = 64;
    m.bake.pr_tables = t;
    m.bake.pr_samples = {{0.5f, 2.0f, 64.0f, 0.9, 0.8}, {1.0f, 1.0f, 2.0f, 1.0, 1.0}};
    return encode_glb(m);
  }();
  return bytes;
}

// decode_glb of the baked model with `edit` applied to its extras.forest must fail with an
// InputError whose message names the file and contains `expected`.
void expect_refused(const std::function<void(nlohmann::json&)>& edit, const std::string& expected) {
  std::vector<uint8_t> bytes = with_forest_extras(baked_glb(), edit);
  try {
    decode_glb(bytes, "tampered.glb");
    ADD_FAILURE() << "accepted; expected an error naming " << expected;
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("tampered.glb"), std::string::npos) << what;
    EXPECT_NE(what.find(expected), std::string::npos) << what;
  }
}

}  // namespace

TEST(BakeIo, BakedAssetLoadsUntouched) {
  // The reference for the tests below: the untampered asset (and its JSON rewritten as is) loads.
  TreeModel m = decode_glb(baked_glb(), "baked.glb");
  EXPECT_TRUE(m.bake.baked());
  ASSERT_TRUE(m.bake.hull.has_value());
  EXPECT_FALSE(m.bake.hull->points.empty());
  TreeModel same = decode_glb(with_forest_extras(baked_glb(), [](nlohmann::json&) {}), "same.glb");
  EXPECT_EQ(same.bake.hull->points, m.bake.hull->points);
  // A derived value off by less than the tolerance is accepted.
  decode_glb(with_forest_extras(baked_glb(), [](nlohmann::json& f) { f["pr_tables"]["d"][5] = f["pr_tables"]["d"][5].get<double>() + 1e-7; }),
             "rounded.glb");
}

TEST(BakeIo, DerivedTableValuesAreChecked) {
  // lambda, d and lambda_cook are stored for readers of the file, but follow from the index:
  // a table that disagrees with its derivation was measured elsewhere (or edited).
  expect_refused([](nlohmann::json& f) { f["pr_tables"]["d"][3] = 0.5; }, "extras.forest.pr_tables.d: d[3]");
  expect_refused([](nlohmann::json& f) { f["pr_tables"]["lambda"][7] = f["pr_tables"]["lambda"][8]; },
                 "extras.forest.pr_tables.lambda: lambda[7]");
  expect_refused([](nlohmann::json& f) { f["pr_tables"]["lambda_cook"][0] = 0.99; },
                 "extras.forest.pr_tables.lambda_cook: lambda_cook[0]");
  expect_refused([](nlohmann::json& f) { f["pr_tables"]["d"].erase(0); }, "extras.forest.pr_tables.d");
  expect_refused([](nlohmann::json& f) { f["pr_tables"]["lambda_far"][1] = 0.05; },
                 "extras.forest.pr_tables.lambda_far: lambda_far[1]");
  expect_refused([](nlohmann::json& f) { f["pr_tables"]["per_size"][2]["s_far"].erase(0); },
                 "extras.forest.pr_tables.per_size[2].s_far");
  expect_refused([](nlohmann::json& f) { f["pr_tables"]["per_size"][1]["q_far"][0] = "x"; },
                 "extras.forest.pr_tables.per_size[1].q_far");
  expect_refused([](nlohmann::json& f) { f["pr_tables"]["per_size"][0]["q_low"][20] = 2.0; },
                 "extras.forest.pr_tables.per_size[0].q_low");
  expect_refused([](nlohmann::json& f) { f["pr_tables"].erase("lambda"); }, "extras.forest.pr_tables.lambda");
  // Measured tables out of range, as before.
  expect_refused([](nlohmann::json& f) { f["pr_tables"]["per_size"][4]["lambda_opt"][2] = 1.5; },
                 "extras.forest.pr_tables.per_size[4].lambda_opt");
  expect_refused([](nlohmann::json& f) { f["pr_tables"]["per_size"].erase(5); }, "extras.forest.pr_tables.per_size");
  expect_refused([](nlohmann::json& f) { f["pr_tables"]["sizes"][2] = 17.0; }, "extras.forest.pr_tables.sizes: sizes[2]");
  expect_refused([](nlohmann::json& f) { f["pr_tables"]["size0"] = -3.0; }, "extras.forest.pr_tables.size0");
}

TEST(BakeIo, TablesOfAnOlderFormatAskForABake) {
  // Format 1 had one size: s_opt and lambda_opt at the top, no format key.
  expect_refused([](nlohmann::json& f) {
    nlohmann::json& t = f["pr_tables"];
    t["s_opt"] = t["per_size"][0]["s_opt"];
    t["lambda_opt"] = t["per_size"][0]["lambda_opt"];
    t.erase("per_size");
    t.erase("format");
  }, "extras.forest.pr_tables.format: missing: PR tables of format 1 (measured at one size); generate the model again");
  // Format 2 had no far samples: s_opt below λ = 1/20 was extrapolated, not measured.
  expect_refused([](nlohmann::json& f) {
    f["pr_tables"]["format"] = 2;
    f["pr_tables"].erase("lambda_far");
    for (auto& s : f["pr_tables"]["per_size"])
      for (const char* k : {"s_far", "q_far", "q_inverse_far", "q_low", "q_low_far"}) s.erase(k);
  }, "extras.forest.pr_tables.format: expected 3");
}

TEST(BakeIo, HullSamplesAreChecked) {
  expect_refused([](nlohmann::json& f) { f["hull_sample_normals"].erase(0); },
                 "extras.forest.hull_sample_normals: expected one normal per hull sample");
  expect_refused([](nlohmann::json& f) {
    auto& n = f["hull_sample_normals"][4];
    for (auto& c : n) c = c.get<double>() * 1.1;
  }, "extras.forest.hull_sample_normals[4]: not unit length");
  expect_refused([](nlohmann::json& f) { f["hull_sample_normals"][0] = {0.0, 0.0, 0.0}; },
                 "extras.forest.hull_sample_normals[0]: not unit length");
  expect_refused([](nlohmann::json& f) { f["hull_samples"][2] = {0.0, "x", 1.0}; }, "extras.forest.hull_samples[2]");
  expect_refused([](nlohmann::json& f) { f["hull_samples"][1] = {0.0, 1.0}; }, "extras.forest.hull_samples[1]");
  expect_refused([](nlohmann::json& f) { f.erase("hull_iso"); }, "extras.forest.hull_iso: missing");
  expect_refused([](nlohmann::json& f) { f["hull_radius"] = -1.0; }, "extras.forest.hull_radius");
}

TEST(BakeIo, OrderFlagsAndSamplesAreChecked) {
  expect_refused([](nlohmann::json& f) { f["priority"] = "tallest"; }, "extras.forest.priority: unknown priority 'tallest'");
  expect_refused([](nlohmann::json& f) { f["priority"] = 3; }, "extras.forest.priority");
  // The tables were measured with the leaves in another order.
  expect_refused([](nlohmann::json& f) { f["priority"] = "random"; }, "extras.forest.pr_tables.priority");
  // baked is derived: true exactly when there are tables (and their PR samples).
  expect_refused([](nlohmann::json& f) { f.erase("pr_tables"); }, "extras.forest.pr_tables: missing");
  expect_refused([](nlohmann::json& f) { f["baked"] = false; }, "extras.forest.baked");
  expect_refused([](nlohmann::json& f) { f.erase("pr_samples"); }, "extras.forest.pr_samples: missing");
  expect_refused([](nlohmann::json& f) { f["pr_samples"][1] = {1.0, 1.0, 2.0, 1.5, 1.0}; }, "extras.forest.pr_samples[1]");
  expect_refused([](nlohmann::json& f) { f["pr_samples"][0] = {0.5, 2.0, 0.9, 0.8}; }, "extras.forest.pr_samples[0]");
}

TEST(BakeIo, BakeKeysInMetaAreAProgrammingError) {
  // Bake data lives in TreeModel::bake; a stray key in meta would be written twice.
  TreeModel m = decode_glb(baked_glb(), "baked.glb");
  m.meta["hull_iso"] = 0.05;
  EXPECT_THROW(encode_glb(m), std::logic_error);
}

TEST(PrTablesMath, LowQuantileTakesTheLowNearestRank) {
  // q_low and the bench's per-tree 10th percentile: rank ⌊0.1 (n − 1)⌋ of the sorted values,
  // one render's own Q, never a mix of two.
  std::vector<float> q(20);
  std::iota(q.begin(), q.end(), 1.0f);
  std::reverse(q.begin(), q.end());
  EXPECT_EQ(low_quantile(q, 0.1), 2.0f);  // rank 1 of 0 … 19
  EXPECT_EQ(low_quantile(q), 2.0f) << "TARGET_LOW_QUANTILE is 0.1";
  EXPECT_EQ(low_quantile(q, 0.0), 1.0f);
  EXPECT_EQ(low_quantile(q, 1.0), 20.0f);
  EXPECT_EQ(low_quantile({0.5f, 0.9f}, 0.5), 0.5f);
  EXPECT_EQ(low_quantile({}, 0.1), 1.0f) << "nothing covered: nothing lost";
}
