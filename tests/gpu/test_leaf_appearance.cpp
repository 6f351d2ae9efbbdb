// Leaves look the same near and far: a wall of needle cards (the conifer presets' texture)
// rendered at 8x the texel footprint (as at 8x the distance) keeps its coverage and color,
// with and without MSAA (alpha as a sample mask), and the rendered frame stays opaque.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/render/leaf_textures.h"
#include "engine/render/renderer.h"
#include "engine/scene/scene.h"
#include "generators/mesh/leaf_texture.h"
#include "generators/mesh/mesher.h"
#include "tests/gpu/gpu_scenes.h"
#include "tests/gpu/validated_gpu_test.h"

using namespace forest;
using namespace forest::test;

namespace {

// The camera 8 m before the wall (at z = 0) over flat ground; no species: the test places its model.
const std::string kWallScene = SceneText{.width = std::nullopt,
                                         .height = std::nullopt,
                                         .samples = std::nullopt,
                                         .render = "mode = \"full\"\n",
                                         .position = {0.0f, 6.0f, -8.0f},
                                         .target = {0.0f, 6.0f, 0.0f},
                                         .fov = 40.0f,
                                         .terrain_size = 100.0f,
                                         .terrain_resolution = 4,
                                         .terrain_height = 0.0f,
                                         .terrain_seed = std::nullopt,
                                         .species = ""}
                                   .str();

// A "tree" that is a wall of needle cards in the plane z = 0, tiled edge to edge so that the
// wall covers exactly what the texture covers; the bark is one small triangle behind it.
TreeModel leaf_wall(Image8 texture) {
  TreeModel m;
  m.leaf_card = make_leaf_card(LeafShape::needles);
  m.leaf_texture = std::move(texture);
  m.leaf_color = {0.04f, 0.14f, 0.07f};  // picea_abies
  const float w = leaf_card_aspect(LeafShape::needles);
  const int columns = 16, rows = 8;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) {
      LeafPlacement l;
      l.position = {(float(c) - float(columns - 1) * 0.5f) * w, 2.0f + float(r), 0.0f};
      m.leaves.push_back(l);
    }
  m.branches.vertices = {{{0, 5, 1}, {0, 0, -1}, {}}, {{0.1f, 5, 1}, {0, 0, -1}, {}}, {{0, 5.1f, 1}, {0, 0, -1}, {}}};
  m.branches.indices = {0, 1, 2};
  m.bounding_sphere = glm::vec4(0.0f, 6.0f, 0.0f, 7.0f);
  return m;
}

struct Measure {
  glm::vec3 mean{0.0f};  // linear RGB over the central box, which only the wall covers
  bool opaque = true;    // every pixel of the frame has alpha 255
};

float linear(uint8_t v) {
  float c = float(v) / 255.0f;
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

class LeafAppearance : public ValidatedGpuTest {
 protected:
  Measure render(const TreeModel& model, uint32_t size, uint32_t samples) {
    SceneDesc desc = parse_scene(kWallScene, "wall.toml");
    desc.trees = {TreeDesc{}};
    Scene s = scene_of(std::move(desc), {model});
    Renderer renderer(ctx_, s, size, size, samples);
    FrameImage image;
    renderer.render(s.desc.camera, &image);
    Measure m;
    for (uint32_t y = 0; y < size; ++y)
      for (uint32_t x = 0; x < size; ++x) m.opaque = m.opaque && image.pixel(x, y)[3] == 255;
    // The central half of the frame sees +-1.46 m around the wall's middle: wall only.
    size_t n = 0;
    for (uint32_t y = size / 4; y < 3 * size / 4; ++y)
      for (uint32_t x = size / 4; x < 3 * size / 4; ++x, ++n)
        for (int c = 0; c < 3; ++c) m.mean[c] += linear(image.pixel(x, y)[c]);
    m.mean /= float(n);
    return m;
  }
};

}  // namespace

TEST_F(LeafAppearance, NeedleCoverageAndColorKeptAtDistance) {
  const Image8 needles = make_leaf_texture(LeafShape::needles);
  Image8 solid = needles;  // same RGB, every texel opaque: the leaf color alone
  for (size_t i = 3; i < solid.rgba.size(); i += 4) solid.rgba[i] = 255;
  TreeModel textured = leaf_wall(needles), opaque = leaf_wall(solid), bare = leaf_wall(needles);
  bare.leaves.clear();
  const float texture_coverage = alpha_coverage(needles, 1.0f);
  ASSERT_GT(texture_coverage, 0.2f);
  ASSERT_LT(texture_coverage, 0.8f);

  for (uint32_t samples : {1u, 4u}) {
    float coverage[2];
    glm::vec3 leaf[2];
    const uint32_t sizes[2] = {256, 24};  // a card spans ~44 px, then ~4 px
    for (int i = 0; i < 2; ++i) {
      Measure wall = render(textured, sizes[i], samples), lit = render(opaque, sizes[i], samples),
              behind = render(bare, sizes[i], samples);
      EXPECT_TRUE(wall.opaque) << "leaf coverage leaked into the frame's alpha (" << sizes[i] << " px, " << samples
                               << " samples)";
      // The mean over the box mixes leaf and background by the covered fraction.
      glm::vec3 d = behind.mean - lit.mean;
      coverage[i] = glm::dot(behind.mean - wall.mean, d) / glm::dot(d, d);
      leaf[i] = lit.mean;
    }
    SCOPED_TRACE(std::to_string(samples) + " samples");
    EXPECT_NEAR(coverage[0], texture_coverage, 0.08f) << "near";
    EXPECT_NEAR(coverage[1], coverage[0], 0.08f) << "far: alpha-tested needles thinned out by the mips";
    // The leaf's color (its model color x per-leaf color x lit texture RGB) does not change with
    // the mip level: within 10% per channel, and green stays the dominant channel.
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(leaf[1][c], leaf[0][c], 0.1f * leaf[0][c] + 1e-3f) << "channel " << c;
    EXPECT_GT(leaf[0].g, 1.5f * leaf[0].r);
    EXPECT_GT(leaf[0].g, 1.5f * leaf[0].b);
  }
}

TEST_F(LeafAppearance, UndersidesArePalerAndLessSaturated) {
  // The wall faces +z, away from the camera: it shows the cards' undersides. Turned about +y
  // it shows their upper sides, with the same shading normal (toward the camera) and so the
  // same light: the colours differ by the albedo alone.
  Image8 solid = make_leaf_texture(LeafShape::needles);
  for (size_t i = 3; i < solid.rgba.size(); i += 4) solid.rgba[i] = 255;
  TreeModel under = leaf_wall(solid), upper = leaf_wall(solid);
  for (LeafPlacement& l : upper.leaves) l.rotation = glm::quat(0.0f, 0.0f, 1.0f, 0.0f);
  const glm::vec3 u = render(under, 128, 1).mean, t = render(upper, 128, 1).mean;
  auto luma = [](glm::vec3 c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; };
  EXPECT_GT(luma(u), 1.1f * luma(t)) << "paler underside";
  EXPECT_LT(luma(u), 1.35f * luma(t)) << "subtly";
  EXPECT_LT(u.g / u.r, t.g / t.r) << "less saturated underside";
  EXPECT_GT(u.g, u.r);  // still green
}
