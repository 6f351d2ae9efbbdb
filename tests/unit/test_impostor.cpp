// Impostors on the CPU: the hemi-octahedral view layout shared by the bake and the shaders
// (shaders/impostor_math.h), the atlas arrays' layers and mip chains (impostor_textures.h),
// and the impostor's round trip through a .glb.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "engine/render/impostor_textures.h"
#include "engine/scene/camera.h"
#include "generators/asset/asset_io.h"
#include "generators/core/input_error.h"
#include "generators/species/registry.h"
#include "impostor_math.h"

using namespace forest;
using namespace forest::impostor;

namespace {

glm::vec3 random_upper_direction(std::mt19937& rng) {
  std::normal_distribution<float> n;
  glm::vec3 d(n(rng), std::abs(n(rng)), n(rng));
  return glm::normalize(d);
}

Image8 filled(uint32_t size, glm::u8vec4 c) {
  Image8 img;
  img.width = img.height = size;
  for (uint32_t i = 0; i < size * size; ++i) img.rgba.insert(img.rgba.end(), {c.r, c.g, c.b, c.a});
  return img;
}

}  // namespace

TEST(Impostor, HemiOctahedralRoundTripsTheUpperHemisphere) {
  std::mt19937 rng(3);
  for (int k = 0; k < 2000; ++k) {
    glm::vec3 d = random_upper_direction(rng);
    glm::vec2 e = hemi_oct_encode(d);
    ASSERT_LE(std::abs(e.x), 1.0f + 1e-6f);
    ASSERT_LE(std::abs(e.y), 1.0f + 1e-6f);
    ASSERT_LT(glm::length(hemi_oct_decode(e) - d), 1e-5f) << d.x << " " << d.y << " " << d.z;
  }
  // Below the horizon: taken at the horizon, same azimuth.
  glm::vec3 below = hemi_oct_decode(hemi_oct_encode(glm::vec3(0.6f, -0.5f, 0.8f)));
  EXPECT_NEAR(below.y, 0.0f, 1e-6f);
  EXPECT_NEAR(std::atan2(below.z, below.x), std::atan2(0.8f, 0.6f), 1e-5f);
}

TEST(Impostor, ViewGridCoversTheHemisphereHorizonToZenith) {
  float highest = 0.0f;
  for (uint32_t j = 0; j < IMPOSTOR_GRID; ++j)
    for (uint32_t i = 0; i < IMPOSTOR_GRID; ++i) {
      glm::vec3 d = impostor_view_direction(i, j);
      EXPECT_NEAR(glm::length(d), 1.0f, 1e-5f);
      EXPECT_GE(d.y, -1e-6f);
      glm::vec2 g = impostor_grid_position(d);  // a view's own direction is its grid vertex
      EXPECT_NEAR(g.x, float(i), 1e-3f);
      EXPECT_NEAR(g.y, float(j), 1e-3f);
      bool border = i == 0 || j == 0 || i == IMPOSTOR_GRID - 1 || j == IMPOSTOR_GRID - 1;
      if (border) EXPECT_NEAR(d.y, 0.0f, 1e-5f) << i << "," << j;  // the border looks from the horizon
      highest = std::max(highest, d.y);
    }
  EXPECT_GT(highest, 0.99f);  // the middle views look from (almost) straight above
  // Neighbouring views are less than 22° apart (at most 21.4° on a 12 × 12 grid, near the
  // horizon): any viewer is that close to three of them.
  for (uint32_t j = 0; j + 1 < IMPOSTOR_GRID; ++j)
    for (uint32_t i = 0; i + 1 < IMPOSTOR_GRID; ++i)
      EXPECT_GT(glm::dot(impostor_view_direction(i, j), impostor_view_direction(i + 1, j)), std::cos(glm::radians(22.0f)));
}

// The image axes the shaders assume are the bake camera's: a point right of the centre along
// impostor_right lands right of the frame's centre, one along impostor_up above it.
TEST(Impostor, ViewAxesAreTheBakeCamerasImageAxes) {
  for (uint32_t j = 0; j < IMPOSTOR_GRID; ++j)
    for (uint32_t i = 0; i < IMPOSTOR_GRID; ++i) {
      glm::vec3 d = impostor_view_direction(i, j), c(1.0f, 4.0f, -2.0f);
      CameraDesc cam;
      cam.target = c;
      cam.position = c + d * 6.0f;
      cam.ortho_height = 6.0f;
      cam.near = 1.0f;
      cam.far = 20.0f;
      CameraMatrices m = camera_matrices(cam, 1.0f);
      glm::vec3 centre = project_to_pixel(m, c, 64.0f, 64.0f);
      glm::vec3 right = project_to_pixel(m, c + impostor_right(d), 64.0f, 64.0f);
      glm::vec3 up = project_to_pixel(m, c + impostor_up(d), 64.0f, 64.0f);
      EXPECT_NEAR(right.x - centre.x, 64.0f / 6.0f, 1e-3f) << i << "," << j;
      EXPECT_NEAR(right.y - centre.y, 0.0f, 1e-3f);
      EXPECT_NEAR(up.y - centre.y, -64.0f / 6.0f, 1e-3f) << i << "," << j;  // image rows go down
      EXPECT_NEAR(up.x - centre.x, 0.0f, 1e-3f);
    }
}

TEST(Impostor, OctahedralNormalsRoundTrip) {
  std::mt19937 rng(5);
  std::normal_distribution<float> n;
  for (int k = 0; k < 2000; ++k) {
    glm::vec3 v = glm::normalize(glm::vec3(n(rng), n(rng), n(rng)));
    glm::vec2 e = oct_encode_normal(v);
    ASSERT_GE(e.x, 0.0f);
    ASSERT_LE(e.y, 1.0f);
    // Stored as 8 bits per channel: within about a degree.
    glm::vec2 q = glm::round(e * 255.0f) / 255.0f;
    ASSERT_GT(glm::dot(oct_decode_normal(q), v), std::cos(glm::radians(1.5f)));
  }
}

TEST(Impostor, NormalMipsAverageOnlyCoveredTexels) {
  Image8 normals = filled(2, {0, 0, 0, 255}), albedo = filled(2, {0, 0, 0, 0});
  normals.rgba[0] = 200, normals.rgba[1] = 100, normals.rgba[2] = 50;  // texel (0, 0), the only covered one
  albedo.rgba[3] = 255;
  Image8 next = downsample_by_coverage(normals, albedo);
  ASSERT_EQ(next.width, 1u);
  EXPECT_EQ(next.rgba[0], 200);
  EXPECT_EQ(next.rgba[1], 100);
  EXPECT_EQ(next.rgba[2], 50);
  Image8 empty = downsample_by_coverage(normals, filled(2, {0, 0, 0, 0}));
  EXPECT_EQ(empty.rgba[0], 128);  // nothing covered: the neutral normal
}

TEST(Impostor, ArraysGiveLayersOnlyToModelsWithAnImpostor) {
  TreeModel plain, baked;
  baked.impostor.albedo = filled(IMPOSTOR_ATLAS_SIZE, {10, 200, 30, 255});
  baked.impostor.normal_depth = filled(IMPOSTOR_ATLAS_SIZE, {128, 128, 200, 255});
  ImpostorArrays a = build_impostor_arrays({&plain, &baked, &plain});
  EXPECT_EQ(a.layer, (std::vector<uint32_t>{0, 1, 0}));
  EXPECT_EQ(a.albedo.layers, 2u);
  EXPECT_EQ(a.albedo.size, uint32_t(IMPOSTOR_ATLAS_SIZE));
  // Down to one texel per view: IMPOSTOR_GRID texels across the last level.
  EXPECT_EQ(IMPOSTOR_ATLAS_SIZE >> (a.albedo.mips - 1), IMPOSTOR_GRID);
  size_t per_layer = 0;
  for (uint32_t m = 0, s = a.albedo.size; m < a.albedo.mips; ++m, s /= 2) per_layer += size_t(s) * s * 4;
  ASSERT_EQ(a.albedo.texels.size(), 2 * per_layer);
  EXPECT_EQ(a.albedo.texels[per_layer + 1], 200);  // layer 1 holds the model's atlas
  EXPECT_EQ(a.albedo.texels[3], 0);                // layer 0 is empty
  ImpostorArrays none = build_impostor_arrays({&plain});
  EXPECT_EQ(none.albedo.size, 1u);
  EXPECT_EQ(none.layer, std::vector<uint32_t>{0});
}

TEST(Impostor, RoundTripsThroughAGlbAndRefusesBadTables) {
  const char* species = R"(method = "lsystem"
iterations = 2
axiom = "X"
angle = 25.0
step = 0.3
shoots_per_tip = 2
leaf_size = 0.2
[[production]]
predecessor = "X"
successor = "F[+X]F[-X]"
)";
  TreeModel m = generate_from_species_text(species, "tiny.toml", {3});
  m.impostor.albedo = filled(IMPOSTOR_ATLAS_SIZE, {90, 140, 20, 255});
  m.impostor.albedo.rgba[7] = 17;
  m.impostor.normal_depth = filled(IMPOSTOR_ATLAS_SIZE, {128, 60, 200, 255});
  m.impostor.q = {0.5f, 0.6f, 0.7f, 0.8f, 0.85f, 0.9f};
  m.impostor.cutoff = 0.3f;
  TreeModel back = decode_glb(encode_glb(m), "m.glb");
  ASSERT_TRUE(back.impostor.present());
  EXPECT_EQ(back.impostor.q, m.impostor.q);
  EXPECT_FLOAT_EQ(back.impostor.cutoff, 0.3f);
  EXPECT_EQ(back.impostor.albedo.rgba, m.impostor.albedo.rgba);
  EXPECT_EQ(back.impostor.normal_depth.rgba, m.impostor.normal_depth.rgba);
  EXPECT_FALSE(decode_glb(encode_glb(TreeModel(back)), "m.glb").impostor.q.empty());

  m.impostor.q.pop_back();  // one size short
  try {
    decode_glb(encode_glb(m), "bad.glb");
    FAIL() << "accepted an impostor with 5 qualities";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.glb"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("forest_impostor.q"), std::string::npos) << e.what();
  }
}
