// Occlusion feedback on the CPU side (Neubert 2012 §7.4): the hysteresis shared with cull.comp,
// the per-model sample points, and the scene-file switch.
#include <gtest/gtest.h>

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

TEST(OcclusionSamples, BakedHullSamplesOnTheOuterShell) {
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
  // Malformed samples in an asset are input errors naming the key.
  m.meta["hull_sample_normals"].erase(0);
  EXPECT_THROW(occlusion_samples(m), InputError);
  m.meta["hull_samples"] = nlohmann::json::array({{0.0, "x", 1.0}});
  m.meta["hull_sample_normals"] = nlohmann::json::array({{0.0, 1.0, 0.0}});
  try {
    occlusion_samples(m);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("hull_samples[0]"), std::string::npos) << e.what();
  }
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
