// Crown self-shadowing baked from the metaball hull (generators/bake/hull/hull_depth.h) and
// its run-time evaluation (shaders/crown_light.h): depths in a synthetic ball, determinism,
// the asset round trip and refusals, and the overhead-sun property on a real species.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <string>

#include <glm/gtc/quaternion.hpp>

#include "crown_light.h"
#include "generators/asset/asset_io.h"
#include "generators/bake/hull/hull.h"
#include "generators/bake/hull/hull_depth.h"
#include "generators/bake/priority/priority.h"
#include "generators/core/input_error.h"
#include "generators/species/registry.h"
#include "generators/tree/crown_depth.h"

using namespace forest;

namespace {

constexpr float kBallRadius = 2.0f, kFieldRadius = 0.3f, kIso = 0.05f;

// Points on a grid of 0.15 m inside a ball of radius 2 m about the origin.
std::vector<glm::vec3> ball_points() {
  std::vector<glm::vec3> p;
  const float h = 0.15f;
  for (float z = -kBallRadius; z <= kBallRadius; z += h)
    for (float y = -kBallRadius; y <= kBallRadius; y += h)
      for (float x = -kBallRadius; x <= kBallRadius; x += h)
        if (glm::length(glm::vec3(x, y, z)) <= kBallRadius) p.push_back({x, y, z});
  return p;
}

// Index of +x, −x, +y, −y, +z, −z in a CrownCube.
enum { kPX, kNX, kPY, kNY, kPZ, kNZ };

}  // namespace

TEST(CrownShadow, BallOfLeaves) {
  MetaballField field = make_metaball_field(ball_points(), kFieldRadius);
  std::vector<glm::vec3> probes = {{0.0f, 0.0f, 0.0f}, {kBallRadius - 0.2f, 0.0f, 0.0f}};
  std::vector<CrownCube> d = crown_depths(field, kIso, probes);
  ASSERT_EQ(d.size(), 2u);
  // The centre: every depth about the ball radius (the hull reaches ~0.27 m past the last
  // centres at this field radius and iso).
  for (int k = 0; k < 6; ++k) {
    EXPECT_GT(d[0][size_t(k)], kBallRadius - 0.1f) << "centre, depth " << k;
    EXPECT_LT(d[0][size_t(k)], kBallRadius + 0.45f) << "centre, depth " << k;
  }
  // Near the +x surface: little crown toward +x, almost the diameter toward −x.
  EXPECT_LT(d[1][kPX], 0.6f);
  EXPECT_GT(d[1][kNX], 2.0f * kBallRadius - 0.6f);
  EXPECT_GT(d[1][kPY], 0.5f);  // sideways: a chord of the ball
  // The fit on a probe direction: D(ω) close to the sampled chord (−x hemisphere mostly).
  glm::vec3 w = glm::normalize(glm::vec3(-1.0f, 1.0f, 0.0f));
  float fitted = crown::crown_depth_toward({d[1][kPX], d[1][kPY], d[1][kPZ]}, {d[1][kNX], d[1][kNY], d[1][kNZ]}, w);
  EXPECT_GT(fitted, 1.0f);
}

TEST(CrownShadow, Deterministic) {
  std::vector<glm::vec3> pts = ball_points();
  MetaballField field = make_metaball_field(pts, kFieldRadius);
  std::vector<glm::vec3> probes(pts.begin(), pts.begin() + std::min<size_t>(pts.size(), 2000));
  std::vector<CrownCube> a = crown_depths(field, kIso, probes), b = crown_depths(field, kIso, probes);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(CrownCube)), 0);
}

TEST(CrownShadow, ExtinctionFromLeafAreaAndHullVolume) {
  // A unit cube (outward, counter-clockwise) has volume 1.
  Mesh cube;
  for (int i = 0; i < 8; ++i) cube.vertices.push_back({glm::vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1)});
  cube.indices = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
  EXPECT_NEAR(mesh_volume(cube), 1.0, 1e-9);
  // 8 untextured unit-square cards of scale 0.5: area 2 m² in 1 m³ -> κ = 0.5 · 2 = 1.
  TreeModel m;
  m.leaf_card.vertices = {{{-0.5f, 0, 0}}, {{0.5f, 0, 0}}, {{0.5f, 1, 0}}, {{-0.5f, 1, 0}}};
  m.leaf_card.indices = {0, 1, 2, 0, 2, 3};
  for (int i = 0; i < 8; ++i) m.leaves.push_back({glm::vec3(0.5f), glm::quat(1, 0, 0, 0), 0.5f});
  EXPECT_NEAR(crown_extinction(m, cube), 1.0f, 1e-5f);
  m.leaves.assign(1, {glm::vec3(0.5f), glm::quat(1, 0, 0, 0), 0.1f});  // 0.005 -> clamped
  EXPECT_EQ(crown_extinction(m, cube), kMinCrownExtinction);
}

namespace {

TreeModel baked_species(const char* stem) {
  TreeModel m = generate_from_species(std::string(FOREST_SOURCE_DIR) + "/scenes/species/" + stem + ".toml");
  Hull h = build_hull(m.leaves, plant_height(m));
  attach_hull(m, h);
  attach_crown_light(m, h);
  return m;
}

nlohmann::json glb_json(const std::vector<uint8_t>& glb) {
  uint32_t len;
  std::memcpy(&len, glb.data() + 12, 4);
  return nlohmann::json::parse(glb.begin() + 20, glb.begin() + 20 + len);
}

// The .glb with its JSON chunk changed by `edit` (BIN kept).
std::vector<uint8_t> with_json(const std::vector<uint8_t>& glb, const std::function<void(nlohmann::json&)>& edit) {
  uint32_t len;
  std::memcpy(&len, glb.data() + 12, 4);
  nlohmann::json j = glb_json(glb);
  edit(j);
  std::string text = j.dump();
  while (text.size() % 4) text.push_back(' ');
  const size_t bin_at = 20 + size_t(len), bin_size = glb.size() - bin_at;
  std::vector<uint8_t> out(20 + text.size() + bin_size);
  std::memcpy(out.data(), glb.data(), 20);
  std::memcpy(out.data() + 20, text.data(), text.size());
  std::memcpy(out.data() + 20 + text.size(), glb.data() + bin_at, bin_size);
  uint32_t total = uint32_t(out.size()), text_len = uint32_t(text.size());
  std::memcpy(out.data() + 8, &total, 4);
  std::memcpy(out.data() + 12, &text_len, 4);
  return out;
}

nlohmann::json& leaf_attributes(nlohmann::json& j) {
  for (nlohmann::json& n : j["nodes"])
    if (n.value("name", "") == "leaves") return n["extensions"]["EXT_mesh_gpu_instancing"]["attributes"];
  throw std::runtime_error("no leaves node");
}

void expect_refused(const std::vector<uint8_t>& bytes, const std::string& key) {
  try {
    decode_glb(bytes, "tampered.glb");
    ADD_FAILURE() << "accepted; expected an error naming " << key;
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("tampered.glb"), std::string::npos) << what;
    EXPECT_NE(what.find(key), std::string::npos) << what;
  }
}

}  // namespace

TEST(CrownShadow, AssetRoundTripFollowsTheLeafOrder) {
  TreeModel m = baked_species("conifer");
  ASSERT_TRUE(m.bake.crown.has_value());
  ASSERT_EQ(m.bake.crown->depths.size(), m.leaves.size());
  std::vector<LeafPlacement> unordered = m.leaves;
  std::vector<CrownCube> unordered_depths = m.bake.crown->depths;
  Hull h = build_hull(m.leaves, plant_height(m));
  apply_priority(m, h, Priority::combined, 3);
  std::vector<uint8_t> bytes = encode_glb(m);
  TreeModel back = decode_glb(bytes, "x.glb");
  ASSERT_TRUE(back.bake.crown.has_value());
  EXPECT_EQ(back.bake.crown->extinction, m.bake.crown->extinction);
  ASSERT_EQ(back.bake.crown->depths.size(), back.leaves.size());
  // Each leaf read back carries the depths it had before the reorder.
  size_t matched = 0;
  for (size_t k = 0; k < back.leaves.size(); ++k) {
    EXPECT_EQ(back.bake.crown->depths[k], m.bake.crown->depths[k]) << "leaf " << k;
    for (size_t i = 0; i < unordered.size(); ++i)
      if (unordered[i].position == back.leaves[k].position && unordered[i].color == back.leaves[k].color &&
          std::abs(glm::dot(glm::normalize(unordered[i].rotation), back.leaves[k].rotation)) > 1.0f - 1e-6f) {
        EXPECT_EQ(unordered_depths[i], back.bake.crown->depths[k]) << "leaf " << k << " was " << i;
        ++matched;
        break;
      }
    if (k >= 200) break;  // enough to see the permutation carried
  }
  EXPECT_GT(matched, 150u);
  // An asset without crown depths (older bakes) loads with none.
  TreeModel old = m;
  old.bake.crown.reset();
  EXPECT_FALSE(decode_glb(encode_glb(old), "old.glb").bake.crown.has_value());
}

TEST(CrownShadow, BadInputIsRefused) {
  TreeModel m = baked_species("conifer");
  ASSERT_TRUE(m.bake.crown.has_value());
  TreeModel nan = m, negative = m;
  nan.bake.crown->depths[7][kPY] = std::numeric_limits<float>::quiet_NaN();
  negative.bake.crown->depths[3][kNZ] = -0.5f;
  expect_refused(encode_glb(nan), "_CROWN_DEPTH_POS");
  expect_refused(encode_glb(negative), "_CROWN_DEPTH_NEG");
  const std::vector<uint8_t> good = encode_glb(m);
  // Wrong count: the depth accessor declares one element fewer than there are leaves.
  expect_refused(with_json(good, [](nlohmann::json& j) {
                   int a = leaf_attributes(j)["_CROWN_DEPTH_NEG"];
                   j["accessors"][size_t(a)]["count"] = int(j["accessors"][size_t(a)]["count"]) - 1;
                 }),
                 "_CROWN_DEPTH_NEG");
  // One attribute without the other; depths without κ; κ without depths; κ out of range.
  expect_refused(with_json(good, [](nlohmann::json& j) { leaf_attributes(j).erase("_CROWN_DEPTH_POS"); }),
                 "_CROWN_DEPTH_POS");
  expect_refused(with_json(good, [](nlohmann::json& j) { j["extras"]["forest"].erase("crown_extinction"); }),
                 "crown_extinction");
  expect_refused(with_json(good,
                           [](nlohmann::json& j) {
                             leaf_attributes(j).erase("_CROWN_DEPTH_POS");
                             leaf_attributes(j).erase("_CROWN_DEPTH_NEG");
                           }),
                 "_CROWN_DEPTH_POS");
  expect_refused(with_json(good, [](nlohmann::json& j) { j["extras"]["forest"]["crown_extinction"] = -1.0; }),
                 "crown_extinction");
  EXPECT_NO_THROW(decode_glb(good, "good.glb"));
}

namespace {

// The light leaf.vert + tree.frag give a leaf's upper face under a sun toward l (model
// space) at the default sky (scene_file.h): sun term × the crown's transmittance, plus the
// hemisphere ambient × the crown's ambient factor (luminance of common.glsl's shade()).
float leaf_light(const CrownCube& d, float kappa, glm::vec3 n, glm::vec3 l) {
  glm::vec3 pos(d[0], d[2], d[4]), neg(d[1], d[3], d[5]);
  if (n.y < 0.0f) n = -n;  // the face seen from the sun's side
  const float intensity = 3.0f, sky_mid = 0.7152f * 0.5f * (0.35f + 0.72f), ground = 0.19f;
  float sun = std::max(glm::dot(n, l), 0.0f) * crown::crown_sun_transmittance(pos, neg, kappa, l);
  float sky = ground + (sky_mid - ground) * (n.y * 0.5f + 0.5f);
  float ambient = crown::crown_ambient(crown::crown_sky_visibility(pos, neg, kappa));
  return sun * intensity * 0.5f + sky * 0.6f * ambient;
}

}  // namespace

// With the sun overhead, leaves more than 1 m inside the hull are at most 0.6 × as bright as
// those within 0.2 m of its surface.
TEST(CrownShadow, OverheadSunDarkensTheInterior) {
  TreeModel m = baked_species("broadleaf");
  ASSERT_TRUE(m.bake.crown.has_value());
  const float kappa = m.bake.crown->extinction;
  // Depth below the crown's surface: below the convex hull of the leaf centres
  // (generators/tree/convex_hull.h). Not the nearest distance to the metaball mesh: a crown
  // whose leaves line a shell has a hollow hull, whose inner surface is near every leaf (on
  // broadleaf no leaf centre is 1 m from the mesh), and the iso-surface stands ~0.9 r off the
  // outermost centres, so none is within 0.2 m of it either.
  std::vector<glm::vec3> centers;
  for (const LeafPlacement& l : m.leaves) centers.push_back(leaf_center(l));
  std::vector<double> below = depths_below_hull(centers);
  double deep = 0, shallow = 0, sky_mean = 0;
  float sky_min = 1.0f;
  size_t n_deep = 0, n_shallow = 0;
  for (size_t i = 0; i < m.leaves.size(); ++i) {
    const CrownCube& d = m.bake.crown->depths[i];
    float sky = crown::crown_sky_visibility({d[0], d[2], d[4]}, {d[1], d[3], d[5]}, kappa);
    sky_min = std::min(sky_min, sky), sky_mean += sky;
    float b = leaf_light(m.bake.crown->depths[i], kappa, leaf_normal(m.leaves[i]), {0.0f, 1.0f, 0.0f});
    if (below[i] > 1.0) deep += b, ++n_deep;
    if (below[i] < 0.2) shallow += b, ++n_shallow;
  }
  std::printf("sky visibility: min %.3f, mean %.3f (ambient factor >= %.2f)\n", double(sky_min),
              sky_mean / double(m.leaves.size()), double(CROWN_SKY_FLOOR));
  ASSERT_GT(n_deep, 20u);
  ASSERT_GT(n_shallow, 20u);
  deep /= double(n_deep), shallow /= double(n_shallow);
  std::printf("broadleaf: %zu leaves, kappa %.3f /m; > 1 m inside: %zu, mean %.3f; < 0.2 m: %zu, mean %.3f; ratio %.3f\n",
              m.leaves.size(), double(kappa), n_deep, deep, n_shallow, shallow, deep / shallow);
  EXPECT_LE(deep, 0.6 * shallow);
}
