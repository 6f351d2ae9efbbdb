// Occlusion feedback on the CPU side (Neubert 2012 §7.4): the hysteresis shared with cull.comp,
// the per-model sample points, and the scene-file switch.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "engine/occlusion/occlusion_samples.h"
#include "engine/scene/scene_file.h"
#include "generators/bake/hull/hull.h"
#include "generators/core/input_error.h"
#include "generators/species/registry.h"
#include "prune_math.h"

using namespace forest;

TEST(OcclusionFactor, HiddenTreeThinsWithinFourFramesNeverBelowTheFloor) {
  float o = 1.0f;
  int frames = 0;
  while (o > 0.15f && frames < 100) o = prune::occlusion_factor(o, 0.0f), ++frames;
  EXPECT_LE(frames, 4);
  EXPECT_GT(frames, 1) << "a hidden tree should thin out over frames, not pop";
  for (int i = 0; i < 20; ++i) o = prune::occlusion_factor(o, 0.0f);
  EXPECT_FLOAT_EQ(o, OCCLUSION_FLOOR);  // λ_occl = λ · max(f, 0.1)
}

TEST(OcclusionFactor, RisesAtOnceFallsSmoothlyAndHoldsInsideTheBand) {
  EXPECT_FLOAT_EQ(prune::occlusion_factor(0.1f, 1.0f), 1.0f);  // back in view: full detail now
  EXPECT_FLOAT_EQ(prune::occlusion_factor(0.3f, 0.6f), 0.6f);
  EXPECT_FLOAT_EQ(prune::occlusion_factor(0.5f, 0.55f), 0.5f);  // within the band: hold
  float falling = prune::occlusion_factor(1.0f, 0.5f);
  EXPECT_LT(falling, 1.0f);
  EXPECT_GT(falling, 0.5f);
  // A visible fraction flickering by a sample or two does not make λ flicker.
  float o = 0.52f;
  for (int i = 0; i < 10; ++i) {
    float next = prune::occlusion_factor(o, i % 2 ? 0.52f : 0.58f);
    EXPECT_FLOAT_EQ(next, o) << i;
    o = next;
  }
}

namespace {

// A crown whose leaves line a sphere (radius `radius` about `centre`, leaf centres on it,
// Fibonacci spiral): its metaball hull is a thick shell with a closed inner surface around
// the empty middle, so the baked samples fall on both surfaces.
TreeModel hollow_crown(glm::vec3 centre, float radius, uint32_t leaves) {
  TreeModel m;
  const float golden = 2.39996323f;
  const float scale = 0.02f;
  for (uint32_t i = 0; i < leaves; ++i) {
    float y = 1.0f - 2.0f * (float(i) + 0.5f) / float(leaves);
    float ring = std::sqrt(std::max(0.0f, 1.0f - y * y));
    glm::vec3 d(ring * std::cos(golden * float(i)), y, ring * std::sin(golden * float(i)));
    LeafPlacement l;
    l.scale = scale;
    l.position = centre + radius * d - glm::vec3(0.0f, 0.5f * scale, 0.0f);  // card centre on the sphere
    m.leaves.push_back(l);
  }
  m.bounding_sphere = glm::vec4(centre, radius + 0.2f * radius);
  return m;
}

}  // namespace

TEST(OcclusionSamples, BakedHullSamplesOnTheOuterShell) {
  {
    // A hollow hull: two closed surfaces, the outer one seen from outside and an inner one
    // facing the empty middle. Samples on the inner surface are hidden by the tree's own
    // foliage from every side, so occlusion_samples must drop them (its outward ray test)
    // and keep the ones on the outer surface.
    const glm::vec3 c(0.0f, 3.0f, 0.0f);
    const float R = 1.0f;
    TreeModel m = hollow_crown(c, R, 2000);
    HullParams params;
    params.sample_count = 128;
    Hull hull = build_hull(m.leaves, 3.0f, params);  // r = 0.15: a shell of about 0.87 R .. 1.13 R
    ASSERT_FALSE(hull.mesh.indices.empty());
    ASSERT_EQ(hull.samples.size(), 128u);
    // The field is 0 at the centre: the hull really is hollow there.
    size_t inner = 0, outer = 0;
    for (const glm::vec3& p : hull.samples) {
      float d = glm::distance(p, c);
      ASSERT_TRUE(d < 0.95f * R || d > 1.05f * R) << "sample between the shells at " << d;
      (d < R ? inner : outer) += 1;
    }
    ASSERT_GE(inner, 16u) << "the bake put too few samples on the inner surface to test anything";
    ASSERT_GE(outer, 32u);
    attach_hull(m, hull);
    OcclusionSamples s = occlusion_samples(m);
    EXPECT_TRUE(s.from_hull);
    size_t kept_outer = 0;
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const gpu::HullSample& h : s.samples) {
      glm::vec3 p(h.position);
      float d = glm::distance(p, c);
      EXPECT_GT(d, R) << "kept a sample on the inner shell at (" << p.x << ", " << p.y << ", " << p.z << ")";
      if (d > R) ++kept_outer;
      // Its normal points away from the centre: outward on the outer shell.
      EXPECT_GT(glm::dot(glm::vec3(h.normal), p - c), 0.0f);
      lo = glm::min(lo, p - c), hi = glm::max(hi, p - c);
    }
    EXPECT_LE(s.samples.size(), outer) << inner << " inner, " << outer << " outer baked samples";
    // The outer shell is a smooth convex surface: (nearly) all of its samples stay...
    EXPECT_GE(kept_outer * 10, outer * 9) << kept_outer << " of " << outer << " outer samples kept";
    // ...and they cover it on every side.
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_GT(hi[axis], 0.9f * R) << "axis " << axis;
      EXPECT_LT(lo[axis], -0.9f * R) << "axis " << axis;
    }
  }

  TreeModel m = generate_from_species(std::string(FOREST_SOURCE_DIR) + "/scenes/species/broadleaf.toml", GenerateOptions{11});
  Hull hull = build_hull(m.leaves, plant_height(m));
  attach_hull(m, hull);
  OcclusionSamples s = occlusion_samples(m);
  EXPECT_TRUE(s.from_hull);
  EXPECT_GE(s.samples.size(), hull.samples.size() / 2);
  EXPECT_LE(s.samples.size(), hull.samples.size());
  EXPECT_GT(s.margin, 0.0f);
  EXPECT_LT(s.margin, 0.25f * m.bounding_sphere.w);
  for (const gpu::HullSample& h : s.samples) {
    EXPECT_NEAR(glm::length(glm::vec3(h.normal)), 1.0f, 1e-4f);
    // Every kept sample is one of the baked ones.
    bool found = false;
    for (const glm::vec3& p : hull.samples) found |= glm::distance(p, glm::vec3(h.position)) < 1e-5f;
    EXPECT_TRUE(found);
  }
  // Malformed samples in an asset are refused when it is read (test_bake_io.cpp); samples a
  // program got wrong are refused here rather than read out of bounds.
  m.bake.hull->normals.pop_back();
  EXPECT_THROW(occlusion_samples(m), std::invalid_argument);
  m.bake.hull->points = {{0.0f, 1.0f, 0.0f}};
  m.bake.hull->normals = {{0.0f, 0.0f, 0.0f}};
  EXPECT_THROW(occlusion_samples(m), std::invalid_argument);
}

TEST(OcclusionSamples, UnbakedModelsUseTheCrownEllipsoid) {
  TreeModel m;
  m.bounding_sphere = {0.0f, 5.0f, 0.0f, 5.0f};
  for (float x : {-2.0f, 2.0f})
    for (float y : {4.0f, 8.0f}) m.leaves.push_back({{x, y, 0.5f * x}});
  OcclusionSamples s = occlusion_samples(m);
  EXPECT_FALSE(s.from_hull);
  ASSERT_EQ(s.samples.size(), size_t(kEllipsoidOcclusionSamples));
  const glm::vec3 c(0.0f, 6.0f, 0.0f), axes(2.0f, 2.0f, 1.0f);
  for (const gpu::HullSample& h : s.samples) {
    glm::vec3 u = (glm::vec3(h.position) - c) / axes;
    EXPECT_NEAR(glm::length(u), 1.0f, 1e-4f);                            // on the ellipsoid
    EXPECT_GT(glm::dot(glm::vec3(h.normal), glm::vec3(h.position) - c), 0.0f);  // outward
  }
}

TEST(SceneFile, OcclusionSwitch) {
  const std::string dir = std::string(FOREST_SOURCE_DIR) + "/scenes";
  EXPECT_FALSE(parse_scene_text("", "s.toml", dir).occlusion);
  EXPECT_TRUE(parse_scene_text("[render]\nocclusion = true\n", "s.toml", dir).occlusion);
  try {
    parse_scene_text("[render]\nocclusion = 3\n", "s.toml", dir);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("s.toml:2: render.occlusion"), std::string::npos) << e.what();
  }
}
