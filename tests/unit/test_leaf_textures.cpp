// Leaf texture array preparation (CPU side of the engine's leaf textures).
#include <gtest/gtest.h>

#include "engine/render/leaf_textures.h"
#include "generators/mesh/leaf_texture.h"

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
  EXPECT_EQ(d.mips, 3u);  // 32 16 8: the chain stops at 8 x 8
  size_t per_layer = 0;
  for (uint32_t s = 32; s >= 8; s /= 2) per_layer += size_t(s) * s * 4;
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

TEST(LeafTextures, MipsKeepTheAlphaTestedCoverage) {
  // The needle spray: thin needles whose box-filtered alpha falls under the 0.5 cutoff within
  // a few levels (the conifers lost their needles at distance).
  Image8 needles = make_leaf_texture(LeafShape::needles, 128);
  TextureArrayData d = build_leaf_texture_array({&needles}, 128);
  const float full = alpha_coverage(needles, 1.0f);
  ASSERT_GT(full, 0.2f);
  size_t offset = 0;
  for (uint32_t mip = 0, s = 128; mip < d.mips; ++mip, s /= 2) {
    Image8 level;
    level.width = level.height = s;
    level.rgba.assign(d.texels.begin() + long(offset), d.texels.begin() + long(offset + size_t(s) * s * 4));
    offset += size_t(s) * s * 4;
    if (s >= 4) {
      EXPECT_NEAR(alpha_coverage(level, 1.0f), full, 0.05f) << "mip " << mip << " (" << s << " px)";
    }
  }
}

TEST(LeafTextures, CoverageScaleOnlyTouchesAlpha) {
  Image8 ramp = checker(16);  // RGB (200, 100, 50); alpha rising from 0 to 200 along x
  for (uint32_t y = 0; y < 16; ++y)
    for (uint32_t x = 0; x < 16; ++x) ramp.rgba[(size_t(y) * 16 + x) * 4 + 3] = uint8_t(x * 200 / 15);
  const float before = alpha_coverage(ramp, 1.0f);
  EXPECT_NEAR(before, 0.36f, 0.05f);
  for (float target : {0.2f, 0.5f, 0.7f}) {
    Image8 kept = preserve_alpha_coverage(ramp, target);
    EXPECT_NEAR(alpha_coverage(kept, 1.0f), target, 0.03f);
    for (size_t i = 0; i < kept.rgba.size(); i += 4)
      for (size_t ch = 0; ch < 3; ++ch) ASSERT_EQ(kept.rgba[i + ch], ramp.rgba[i + ch]);
  }
}

TEST(LeafTextures, MipColorAveragedInLinearLight) {
  // Opaque black and white texels: the sRGB texture's half-gray is 188, not 128 (averaging
  // the encoded bytes darkens every level); transparent texels of any RGB stay out.
  Image8 img;
  img.width = img.height = 4;
  img.rgba.resize(4 * 4 * 4);
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 4; ++x) {
      uint8_t* p = &img.rgba[(size_t(y) * 4 + x) * 4];
      uint8_t v = (x + y) % 2 ? 255 : 0;
      p[0] = p[1] = p[2] = v, p[3] = 255;
    }
  Image8 half = downsample(img);
  for (size_t i = 0; i < half.rgba.size(); i += 4) EXPECT_NEAR(half.rgba[i], 188, 1);
  // Green opaque texels beside magenta transparent ones: the level stays green.
  for (size_t i = 0; i < img.rgba.size(); i += 4) {
    bool on = (i / 4) % 2 == 0;
    img.rgba[i + 0] = on ? 40 : 255, img.rgba[i + 1] = on ? 120 : 0, img.rgba[i + 2] = on ? 60 : 255;
    img.rgba[i + 3] = on ? 255 : 0;
  }
  half = downsample(img);
  for (size_t i = 0; i < half.rgba.size(); i += 4) {
    EXPECT_NEAR(half.rgba[i + 0], 40, 4);
    EXPECT_NEAR(half.rgba[i + 1], 120, 2);
    EXPECT_NEAR(half.rgba[i + 2], 60, 4);
  }
}
