// The bark texture arrays the engine uploads (engine/render/bark_textures.h): a neutral layer
// for untextured models, one layer per distinct bark, full mip chains, unit normals in every
// mip.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/render/bark_textures.h"
#include "generators/mesh/bark_texture.h"

using namespace forest;

namespace {

TreeModel textured(BarkPattern p, glm::vec3 colour) {
  TreeModel m;
  BarkTextures t = make_bark_textures(p, colour, 64);
  m.bark_texture = t.albedo;
  m.bark_normal = t.normal;
  return m;
}

size_t layer_bytes(uint32_t size, uint32_t mips) {
  size_t n = 0;
  for (uint32_t k = 0; k < mips; ++k) n += size_t(std::max(size >> k, 1u)) * std::max(size >> k, 1u) * 4;
  return n;
}

}  // namespace

TEST(BarkArrays, NeutralLayerSharedLayersAndMips) {
  TreeModel plain;  // no bark textures: layer 0, its colour from bark_color
  TreeModel oak = textured(BarkPattern::furrowed, glm::vec3(0.3f));
  TreeModel oak_again = textured(BarkPattern::furrowed, glm::vec3(0.3f));
  TreeModel birch = textured(BarkPattern::birch, glm::vec3(0.8f));
  BarkTextureArrays a = build_bark_texture_arrays({&plain, &oak, &birch, &oak_again}, 32);
  EXPECT_EQ(a.layer, (std::vector<uint32_t>{0, 1, 2, 1}));
  EXPECT_EQ(a.coloured, (std::vector<uint8_t>{0, 1, 1, 1}));
  ASSERT_EQ(a.albedo.layers, 3u);
  ASSERT_EQ(a.normals.layers, 3u);
  EXPECT_EQ(a.albedo.mips, 6u);  // 32 .. 1
  const size_t per_layer = layer_bytes(32, 6);
  ASSERT_EQ(a.albedo.texels.size(), 3 * per_layer);
  ASSERT_EQ(a.normals.texels.size(), 3 * per_layer);
  // Layer 0: white albedo, flat normal.
  for (size_t i = 0; i < per_layer; i += 4) {
    ASSERT_EQ(a.albedo.texels[i], 255);
    ASSERT_EQ(a.normals.texels[i + 2], 255);
    ASSERT_EQ(a.normals.texels[i], 128);
  }
  // Every stored normal is a unit vector (mips renormalized), pointing out of the bark.
  for (size_t i = 0; i < a.normals.texels.size(); i += 4) {
    glm::vec3 n = glm::vec3(a.normals.texels[i], a.normals.texels[i + 1], a.normals.texels[i + 2]) / 127.5f - 1.0f;
    ASSERT_NEAR(glm::length(n), 1.0f, 0.02f) << i;
    ASSERT_GT(n.z, 0.0f);
  }
  // The smallest mip of a bark layer averages its bark (not left black or white).
  const size_t last = per_layer - 4;
  EXPECT_GT(a.albedo.texels[per_layer + last], 30);
  EXPECT_LT(a.albedo.texels[per_layer + last], 250);
}

TEST(BarkArrays, NormalMipsAverageAndRenormalize) {
  Image8 img;
  img.width = img.height = 2;
  // Two normals tilted ±x and two straight up: the average points up.
  const uint8_t px[4][4] = {{218, 128, 218, 255}, {38, 128, 218, 255}, {128, 128, 255, 255}, {128, 128, 255, 255}};
  for (auto& p : px) img.rgba.insert(img.rgba.end(), p, p + 4);
  Image8 m = downsample_normals(img);
  ASSERT_EQ(m.width, 1u);
  EXPECT_NEAR(m.rgba[0], 128, 1);
  EXPECT_NEAR(m.rgba[1], 128, 1);
  EXPECT_EQ(m.rgba[2], 255);
}
