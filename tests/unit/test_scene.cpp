// Scene files, terrain, placement and camera math (no GPU).
#include <gtest/gtest.h>

#include <cmath>

#include "engine/scene/camera.h"
#include "engine/scene/scene.h"
#include "generators/core/input_error.h"
#include "tests/unit/scene_parse.h"

using namespace forest;
using namespace forest::test;

TEST(SceneFile, DefaultsAndValues) {
  SceneDesc s = parse("[render]\nwidth = 320\nheight = 200\n[camera]\nposition = [1, 2, 3]\nfov = 40\n");
  EXPECT_EQ(s.width, 320u);
  EXPECT_EQ(s.height, 200u);
  EXPECT_EQ(s.camera.position, glm::vec3(1, 2, 3));
  EXPECT_FLOAT_EQ(s.camera.fov_deg, 40.0f);
  EXPECT_EQ(s.placement.count, 0u);
  EXPECT_FALSE(s.leaf_shadows_per_fragment) << "a leaf reads the shadow map once unless asked";
  EXPECT_TRUE(parse("[render]\nleaf_shadows = \"fragment\"\n").leaf_shadows_per_fragment);
}

TEST(SceneFile, ErrorsNameFileLineAndKey) {
  EXPECT_EQ(error_of("[render]\nwidth = 320\nheigth = 2\n"),
            "s.toml:3: render.heigth: unknown key (expected one of: width, height, samples, lod_error_pixels, mode, prune_distance, transition, view, occlusion, shadows, shadow_distance, shadow_resolution, exposure, quality, impostors, leaf_shadows)");
  EXPECT_EQ(error_of("[render]\n\nwidth = -3\n"), "s.toml:3: render.width: must be in [16, 8192], got -3");
  EXPECT_NE(error_of("[render]\nleaf_shadows = \"pixel\"\n").find("s.toml:2: render.leaf_shadows"), std::string::npos);
  EXPECT_EQ(error_of("[camera]\nfov = nan\n"), "s.toml:2: camera.fov: must be a finite number, got nan");
  EXPECT_EQ(error_of("[camera]\nfov = \"wide\"\n"), "s.toml:2: camera.fov: expected a number, got string");
  EXPECT_EQ(error_of("[placement]\ncount = 2.5\n"), "s.toml:2: placement.count: expected an integer, got 2.5");
  EXPECT_NE(error_of("[camera\n").find("s.toml:1: TOML syntax error"), std::string::npos);
  EXPECT_NE(error_of("[camera]\nposition = [0, 5, 0]\ntarget = [0, 5, 0]\n").find("camera.target"), std::string::npos);
  EXPECT_NE(error_of("[placement]\ncount = 4\n").find("species"), std::string::npos);
  EXPECT_NE(error_of("[[species]]\npreset = \"species/broadleaf.toml\"\nmodel = \"x.glb\"\n").find("species[0]"),
            std::string::npos);
  EXPECT_NE(error_of("[placement]\nscale = [2, 1]\n").find("placement.scale"), std::string::npos);
}

TEST(Terrain, DeterministicBoundedAndMeshConsistent) {
  TerrainDesc d;
  d.size = 100.0f;
  d.resolution = 16;
  d.height = 10.0f;
  d.seed = 9;
  Terrain a = make_terrain(d), b = make_terrain(d);
  EXPECT_EQ(a.heights, b.heights);
  d.seed = 10;
  EXPECT_NE(make_terrain(d).heights, a.heights);
  for (float h : a.heights) EXPECT_LE(std::abs(h), 5.0f + 1e-4f);
  Mesh m = a.mesh();
  ASSERT_EQ(m.vertices.size(), 17u * 17u);
  ASSERT_EQ(m.indices.size(), 16u * 16u * 6u);
  for (size_t t = 0; t < m.indices.size(); t += 3) {
    glm::vec3 p0 = m.vertices[m.indices[t]].position, p1 = m.vertices[m.indices[t + 1]].position,
              p2 = m.vertices[m.indices[t + 2]].position;
    EXPECT_GT(glm::cross(p1 - p0, p2 - p0).y, 0.0f) << "triangle " << t / 3 << " does not face up";
  }
  // height_at interpolates the grid exactly at grid points.
  for (const Vertex& v : m.vertices) EXPECT_NEAR(a.height_at(v.position.x, v.position.z), v.position.y, 1e-4f);
}

TEST(Placement, SpacingRegionSlopeAndDeterminism) {
  SceneDesc s = parse(R"(
[terrain]
size = 200
height = 30
[[species]]
preset = "species/broadleaf.toml"
weight = 3
[[species]]
preset = "species/conifer.toml"
weight = 1
[placement]
count = 800
seed = 4
min_spacing = 3.0
radius = 80
center = [10, -5]
max_slope = 30
)");
  Terrain t = make_terrain(s.terrain);
  uint32_t shortfall = 99;
  std::vector<gpu::Instance> a = place_trees(s, t, &shortfall);
  EXPECT_EQ(shortfall, 0u);
  ASSERT_EQ(a.size(), 800u);
  size_t per_species[2] = {0, 0};
  for (size_t i = 0; i < a.size(); ++i) {
    glm::vec3 p(a[i].position_scale);
    EXPECT_LE(glm::length(glm::vec2(p.x - 10.0f, p.z + 5.0f)), 80.0f + 1e-3f);
    EXPECT_GE(t.normal_at(p.x, p.z).y, std::cos(glm::radians(30.0f)) - 1e-5f);
    EXPECT_NEAR(p.y, t.height_at(p.x, p.z), 0.1f);
    EXPECT_GE(a[i].position_scale.w, 0.8f);
    EXPECT_LE(a[i].position_scale.w, 1.2f);
    EXPECT_NEAR(glm::length(a[i].yaw_cos_sin), 1.0f, 1e-5f);
    ASSERT_LT(a[i].model, 2u);
    per_species[a[i].model]++;
    for (size_t j = 0; j < i; ++j)
      ASSERT_GE(glm::distance(glm::vec2(p.x, p.z), glm::vec2(a[j].position_scale.x, a[j].position_scale.z)), 3.0f - 1e-4f);
  }
  // Weights 3:1 -> about 600:200.
  EXPECT_NEAR(double(per_species[0]) / 800.0, 0.75, 0.06);
  std::vector<gpu::Instance> b = place_trees(s, t);
  ASSERT_EQ(b.size(), a.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(gpu::Instance)), 0);
}

TEST(Placement, ReportsShortfallWhenCrowded) {
  SceneDesc s = parse("[[species]]\npreset = \"species/broadleaf.toml\"\n[placement]\ncount = 500\nmin_spacing = 10\nradius = 30\n");
  uint32_t shortfall = 0;
  std::vector<gpu::Instance> a = place_trees(s, make_terrain(s.terrain), &shortfall);
  EXPECT_GT(shortfall, 0u);
  EXPECT_EQ(a.size() + shortfall, 500u);
  EXPECT_LT(a.size(), 45u);  // disc of radius 30 holds few trees 10 m apart
}

TEST(Camera, ProjectionAndFrustum) {
  CameraDesc c;
  c.position = {0, 0, 0};
  c.target = {0, 0, -10};
  c.fov_deg = 90.0f;
  c.far = 100.0f;
  CameraMatrices m = camera_matrices(c, 1.0f);
  glm::vec3 center = project_to_pixel(m, {0, 0, -5}, 100, 100);
  EXPECT_NEAR(center.x, 50.0f, 1e-3f);
  EXPECT_NEAR(center.y, 50.0f, 1e-3f);
  // Up in the world is up in the image (smaller y), reversed Z: nearer is larger depth.
  EXPECT_LT(project_to_pixel(m, {0, 1, -5}, 100, 100).y, 50.0f);
  EXPECT_GT(project_to_pixel(m, {1, 0, -5}, 100, 100).x, 50.0f);
  EXPECT_GT(project_to_pixel(m, {0, 0, -1}, 100, 100).z, project_to_pixel(m, {0, 0, -50}, 100, 100).z);
  auto inside = [&](glm::vec3 p) {
    for (const glm::vec4& pl : m.frustum)
      if (glm::dot(glm::vec3(pl), p) + pl.w < 0.0f) return false;
    return true;
  };
  EXPECT_TRUE(inside({0, 0, -5}));
  EXPECT_TRUE(inside({4.9f, 0, -5}));
  EXPECT_FALSE(inside({5.1f, 0, -5}));   // 90 degrees: the edge is at x = -z
  EXPECT_FALSE(inside({0, 0, 5}));       // behind
  EXPECT_FALSE(inside({0, 0, -101}));    // beyond far
  EXPECT_FALSE(inside({0, -5.2f, -5}));
}
