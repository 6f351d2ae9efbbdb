// Leaf texture array preparation (CPU side of the engine's leaf textures).
#include <gtest/gtest.h>

#include "engine/render/leaf_textures.h"

using namespace forest;

namespace {
Image8 checker(uint32_t size) {
  Image8 img;
  img.width = img.height = size;
  img.rgba.resize(size_t(size) * size * 4);
  for (uint32_t y = 0; y < size; ++y)
    for (uint32_t x = 0; x < size; ++x) {
      uint8_t* p = &img.rgba[(size_t(y) * size + x) * 4];
      bool on = ((x / 2) + (y / 2)) % 2 == 0;
      p[0] = 200, p[1] = 100, p[2] = 50, p[3] = on ? 255 : 0;
    }
  return img;
}
}  // namespace

TEST(LeafTextures, ArrayLayoutAndMipChain) {
  Image8 a = checker(64), empty;
  TextureArrayData d = build_leaf_texture_array({&a, &empty}, 32);
  EXPECT_EQ(d.layers, 2u);
  EXPECT_EQ(d.mips, 6u);  // 32 16 8 4 2 1
  size_t per_layer = 0;
  for (uint32_t s = 32; s >= 1; s /= 2) per_layer += size_t(s) * s * 4;
  ASSERT_EQ(d.texels.size(), 2 * per_layer);
  // The empty image becomes opaque white at every level.
  for (size_t i = per_layer; i < 2 * per_layer; ++i) ASSERT_EQ(d.texels[i], 255);
  // No layer at all still yields one (white) layer so the shader always has a texture.
  EXPECT_EQ(build_leaf_texture_array({}, 8).layers, 1u);
}

TEST(LeafTextures, DownsamplePreservesCoverageAndColor) {
  Image8 c = checker(16);
  Image8 half = downsample(c);
  ASSERT_EQ(half.width, 8u);
  // A 2x2 checker of 2-pixel cells averages 2x2 blocks that are uniform: coverage stays 0 or 1.
  Image8 quarter = downsample(half);
  for (size_t i = 0; i < quarter.rgba.size(); i += 4) {
    EXPECT_NEAR(quarter.rgba[i + 3], 127.5, 1.0);  // half covered
    // Transparent texels do not pull the color toward black.
    EXPECT_NEAR(quarter.rgba[i + 0], 200, 1);
    EXPECT_NEAR(quarter.rgba[i + 1], 100, 1);
  }
}

TEST(LeafTextures, ResampleKeepsSameSizeExact) {
  Image8 c = checker(16);
  EXPECT_EQ(resample(c, 16).rgba, c.rgba);
  Image8 up = resample(c, 32);
  EXPECT_EQ(up.width, 32u);
  EXPECT_EQ(up.rgba.size(), 32u * 32u * 4u);
}
