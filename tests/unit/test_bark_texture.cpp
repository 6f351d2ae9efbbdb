// Procedural bark textures (generators/mesh/bark_texture.h): seamless tiles whose albedo and
// normal map come from one height field, oriented along the branch, coloured by bark_color.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "generators/mesh/bark_texture.h"

using namespace forest;

namespace {

constexpr BarkPattern kPatterns[] = {BarkPattern::furrowed, BarkPattern::smooth, BarkPattern::birch,
                                     BarkPattern::scaly,    BarkPattern::plated, BarkPattern::generic};

float srgb_to_linear(uint8_t v) {
  float c = float(v) / 255.0f;
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// Luminance (linear) of texel (x, y), wrapped.
float luma(const Image8& img, int x, int y) {
  x = (x % int(img.width) + int(img.width)) % int(img.width);
  y = (y % int(img.height) + int(img.height)) % int(img.height);
  const uint8_t* p = &img.rgba[(size_t(y) * img.width + size_t(x)) * 4];
  return 0.2126f * srgb_to_linear(p[0]) + 0.7152f * srgb_to_linear(p[1]) + 0.0722f * srgb_to_linear(p[2]);
}

// The normal map's slopes: dh/du and dh/dv. glTF's n ∝ (−dh/dX, −dh/dY, 1) with X = +u and
// Y toward the top row, i.e. −v: dh/dv = n.y / n.z.
glm::vec2 slope(const Image8& n, int x, int y) {
  x = (x % int(n.width) + int(n.width)) % int(n.width);
  y = (y % int(n.height) + int(n.height)) % int(n.height);
  const uint8_t* p = &n.rgba[(size_t(y) * n.width + size_t(x)) * 4];
  glm::vec3 v = glm::vec3(p[0], p[1], p[2]) / 127.5f - 1.0f;
  return glm::vec2(-v.x / v.z, v.y / v.z);
}

// Mean absolute difference between column c and c + 1 (wrapped), over all rows; or rows.
double column_step(const Image8& img, int c) {
  double sum = 0.0;
  for (int y = 0; y < int(img.height); ++y) sum += std::abs(luma(img, c, y) - luma(img, c + 1, y));
  return sum / img.height;
}
double row_step(const Image8& img, int r) {
  double sum = 0.0;
  for (int x = 0; x < int(img.width); ++x) sum += std::abs(luma(img, x, r) - luma(img, x, r + 1));
  return sum / img.width;
}

// The height field's Laplacian from the normal map's slopes (central differences).
float laplacian(const Image8& n, int x, int y) {
  return 0.5f * (slope(n, x + 1, y).x - slope(n, x - 1, y).x) + 0.5f * (slope(n, x, y + 1).y - slope(n, x, y - 1).y);
}

}  // namespace

TEST(BarkTexture, NamesRoundTrip) {
  for (BarkPattern p : kPatterns) {
    ASSERT_TRUE(parse_bark_pattern(bark_pattern_name(p)).has_value());
    EXPECT_EQ(*parse_bark_pattern(bark_pattern_name(p)), p);
    EXPECT_GT(bark_tile_meters(p), 0.1f);
    EXPECT_LE(bark_tile_meters(p), 2.0f);
  }
  EXPECT_FALSE(parse_bark_pattern("oak").has_value());
  EXPECT_EQ(bark_tile_meters(BarkPattern::furrowed), 0.5f);
  EXPECT_EQ(bark_tile_meters(BarkPattern::smooth), 1.0f);
}

TEST(BarkTexture, OpaqueDeterministicAndSized) {
  for (BarkPattern p : kPatterns) {
    BarkTextures a = make_bark_textures(p, glm::vec3(0.3f, 0.22f, 0.15f), 64);
    BarkTextures b = make_bark_textures(p, glm::vec3(0.3f, 0.22f, 0.15f), 64);
    EXPECT_EQ(a.albedo.rgba, b.albedo.rgba) << bark_pattern_name(p);
    EXPECT_EQ(a.normal.rgba, b.normal.rgba) << bark_pattern_name(p);
    ASSERT_EQ(a.albedo.width, 64u);
    ASSERT_EQ(a.albedo.rgba.size(), 64u * 64u * 4u);
    ASSERT_EQ(a.normal.rgba.size(), 64u * 64u * 4u);
    for (size_t i = 3; i < a.albedo.rgba.size(); i += 4) ASSERT_EQ(a.albedo.rgba[i], 255);
    for (size_t i = 0; i < a.normal.rgba.size(); i += 4) {
      glm::vec3 n = glm::vec3(a.normal.rgba[i], a.normal.rgba[i + 1], a.normal.rgba[i + 2]) / 127.5f - 1.0f;
      ASSERT_NEAR(glm::length(n), 1.0f, 0.02f);
      ASSERT_GT(n.z, 0.0f);  // out of the bark
    }
  }
}

TEST(BarkTexture, TilesWithoutSeams) {
  // Across the tile's edge (last column to first, last row to first) the albedo changes no
  // more than between neighbouring texels inside it.
  for (BarkPattern p : kPatterns) {
    BarkTextures t = make_bark_textures(p, glm::vec3(0.4f, 0.3f, 0.2f), 128);
    double inside_c = 0.0, inside_r = 0.0;
    for (int i = 0; i < 127; ++i) inside_c += column_step(t.albedo, i) / 127.0, inside_r += row_step(t.albedo, i) / 127.0;
    EXPECT_LT(column_step(t.albedo, 127), 2.5 * inside_c + 1e-4) << bark_pattern_name(p);
    EXPECT_LT(row_step(t.albedo, 127), 2.5 * inside_r + 1e-4) << bark_pattern_name(p);
    double normal_inside = 0.0;
    for (int i = 0; i < 127; ++i) normal_inside += column_step(t.normal, i) / 127.0;
    EXPECT_LT(column_step(t.normal, 127), 2.5 * normal_inside + 1e-4) << bark_pattern_name(p);
  }
}

TEST(BarkTexture, DarkFurrowsAreRecessedAndOrientedAlongTheBranch) {
  // Oak: furrows along v, so the height changes faster across u than along v; the dark
  // texels are in valleys (the height field's Laplacian > 0 there), the bright ones on
  // ridges. Birch: lenticels are dashes along u (the albedo changes faster along v) and
  // recessed. Both read the normal map with +Y toward the top row (−v): a flipped green
  // channel would turn birch's dashes into ridges.
  for (BarkPattern p : {BarkPattern::furrowed, BarkPattern::birch}) {
    BarkTextures t = make_bark_textures(p, glm::vec3(0.5f), 256);
    double across_u = 0.0, along_v = 0.0, albedo_u = 0.0, albedo_v = 0.0;
    std::vector<std::pair<float, float>> tone_and_curvature;
    for (int y = 0; y < 256; ++y)
      for (int x = 0; x < 256; ++x) {
        glm::vec2 s = slope(t.normal, x, y);
        across_u += std::abs(s.x), along_v += std::abs(s.y);
        albedo_u += std::abs(luma(t.albedo, x + 1, y) - luma(t.albedo, x, y));
        albedo_v += std::abs(luma(t.albedo, x, y + 1) - luma(t.albedo, x, y));
        tone_and_curvature.emplace_back(luma(t.albedo, x, y), laplacian(t.normal, x, y));
      }
    std::sort(tone_and_curvature.begin(), tone_and_curvature.end());
    const size_t fifth = tone_and_curvature.size() / 20;  // darkest and brightest 5 %
    double dark = 0.0, bright = 0.0;
    for (size_t i = 0; i < fifth; ++i)
      dark += tone_and_curvature[i].second, bright += tone_and_curvature[tone_and_curvature.size() - 1 - i].second;
    EXPECT_GT(dark, 0.0) << bark_pattern_name(p) << ": dark texels not in valleys";
    EXPECT_GT(dark, bright) << bark_pattern_name(p);
    if (p == BarkPattern::furrowed) {
      EXPECT_GT(across_u, 1.5 * along_v);
      EXPECT_GT(albedo_u, 1.5 * albedo_v);
    } else {
      EXPECT_GT(albedo_v, 1.5 * albedo_u);
    }
  }
}

TEST(BarkTexture, ColourFollowsBarkColorAndBirchStaysWhite) {
  for (BarkPattern p : kPatterns) {
    // Twice the colour, twice the linear albedo (where nothing clamps).
    BarkTextures dim = make_bark_textures(p, glm::vec3(0.1f, 0.08f, 0.06f), 64);
    BarkTextures lit = make_bark_textures(p, glm::vec3(0.2f, 0.16f, 0.12f), 64);
    double a = 0.0, b = 0.0;
    for (size_t i = 0; i < dim.albedo.rgba.size(); i += 4) a += srgb_to_linear(dim.albedo.rgba[i]), b += srgb_to_linear(lit.albedo.rgba[i]);
    EXPECT_NEAR(b / a, 2.0, 0.05) << bark_pattern_name(p);
    EXPECT_EQ(dim.normal.rgba, lit.normal.rgba) << "the relief does not depend on the colour";
    // About the colour on average.
    EXPECT_NEAR(a / double(64 * 64), 0.1, 0.05) << bark_pattern_name(p);
  }
  // Birch with the preset's colour: most of it white.
  BarkTextures birch = make_bark_textures(BarkPattern::birch, glm::vec3(0.80f, 0.78f, 0.72f), 128);
  size_t white = 0;
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x) white += luma(birch.albedo, x, y) > 0.6f;
  EXPECT_GT(white, size_t(0.7 * 128 * 128));
  EXPECT_LT(white, size_t(0.99 * 128 * 128));  // and marked
}
