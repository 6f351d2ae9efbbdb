// The bark's normal map turns the shading the way glTF's convention says: +X of the map along
// +u (around the branch), +Y toward the texture's top row (−v, toward the tip), in the tangent
// frame tree.frag derives from screen-space derivatives. A thick vertical tube with a white
// albedo and a normal map of one constant tilt is lit from the side the tilt faces and from
// the other: the first must be brighter. Also: the albedo texture colours the bark.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/render/renderer.h"
#include "engine/scene/scene.h"
#include "generators/mesh/mesher.h"
#include "generators/methods/lsystem/lsystem.h"
#include "generators/tree/pipe_model.h"
#include "tests/gpu/gpu_scenes.h"
#include "tests/gpu/validated_gpu_test.h"

using namespace forest;
using namespace forest::test;

namespace {

// A solid RGBA8 image.
Image8 solid(glm::u8vec3 rgb) {
  Image8 img;
  img.width = img.height = 16;
  for (int i = 0; i < 16 * 16; ++i) img.rgba.insert(img.rgba.end(), {rgb.r, rgb.g, rgb.b, 255});
  return img;
}

// A straight vertical tube of radius 0.5 m from the ground to 6 m (tip up), bark uv in 0.5 m
// tiles, with the given albedo and a normal map tilted by (tx, ty) in tangent space.
TreeModel tube(glm::vec2 tilt, glm::u8vec3 albedo = {255, 255, 255}) {
  TurtleParams p;
  p.step = 0.5f;
  TreeGraph g = interpret("FFFFFFFFFFFF", p, 1);
  for (TreeNode& n : g.nodes) n.radius = 0.5f;
  MesherParams mp;
  mp.min_sides = mp.max_sides = 24;
  mp.bark_tile_meters = 0.5f;
  TreeModel m;
  m.branches = mesh_branches(g, mp);
  m.bark_tile_meters = 0.5f;
  m.bark_texture = solid(albedo);
  const glm::vec3 n = glm::normalize(glm::vec3(tilt, 1.0f));
  m.bark_normal = solid(glm::u8vec3(glm::round((n * 0.5f + 0.5f) * 255.0f)));
  m.bounding_sphere = glm::vec4(0.0f, 3.0f, 0.0f, 3.2f);
  return m;
}

float linear(uint8_t v) {
  float c = float(v) / 255.0f;
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

class BarkAppearance : public ValidatedGpuTest {
 protected:
  // Mean linear RGB of the tube's middle, seen from 4 m in front (−z), lit from `sun`.
  glm::vec3 render(const TreeModel& model, glm::vec3 sun) {
    SceneDesc desc = flat_ground(96, 96, 60.0f);
    desc.camera.position = {0.0f, 3.0f, -4.0f};
    desc.camera.target = {0.0f, 3.0f, 0.0f};
    desc.camera.fov_deg = 40.0f;
    desc.sky.sun_direction = glm::normalize(sun);
    // A white tube in full sun: a lower exposure keeps it off the tone map's shoulder, where
    // brighter and darker both come out near white.
    desc.exposure = 0.4f;
    desc.trees = {TreeDesc{}};
    Scene s = scene_of(std::move(desc), {model});
    Renderer renderer(ctx_, s, 96, 96, 1);
    FrameImage image;
    renderer.render(s.desc.camera, &image);
    glm::vec3 sum(0.0f);
    int n = 0;
    for (uint32_t y = 40; y < 56; ++y)
      for (uint32_t x = 40; x < 56; ++x, ++n)
        for (int c = 0; c < 3; ++c) sum[c] += linear(image.pixel(x, y)[c]);
    return sum / float(n);
  }
  static float luma(glm::vec3 c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }
};

}  // namespace

TEST_F(BarkAppearance, NormalMapTiltsTowardPlusUAndTowardTheTip) {
  // The camera looks along +z with +y up, so screen right is −x: seen from outside with the
  // tip up, +u runs to the right on the tube's face toward the camera.
  const glm::vec3 from_right{-1.0f, 0.3f, -0.6f}, from_left{1.0f, 0.3f, -0.6f}, from_above{0.0f, 1.0f, -0.3f};
  const float right_u = luma(render(tube({0.7f, 0.0f}), from_right));
  const float left_u = luma(render(tube({-0.7f, 0.0f}), from_right));
  EXPECT_GT(right_u, 1.3f * left_u) << "a normal tilted toward +u must face a sun on +u's side";
  // The same tilts under the mirrored sun swap.
  EXPECT_GT(luma(render(tube({-0.7f, 0.0f}), from_left)), 1.3f * luma(render(tube({0.7f, 0.0f}), from_left)));
  const float up = luma(render(tube({0.0f, 0.7f}), from_above));
  const float down = luma(render(tube({0.0f, -0.7f}), from_above));
  EXPECT_GT(up, 1.3f * down) << "+Y of the normal map must tilt toward the tip (−v)";
}

TEST_F(BarkAppearance, AlbedoTextureColoursTheBark) {
  const glm::vec3 sun{0.0f, 0.6f, -1.0f};
  const glm::vec3 white = render(tube({0.0f, 0.0f}), sun);
  const glm::vec3 red = render(tube({0.0f, 0.0f}, {200, 40, 20}), sun);
  EXPECT_GT(red.r, 2.0f * red.g);
  EXPECT_LT(red.g, 0.5f * white.g);
  // Untextured: the neutral layer, coloured by bark_color alone.
  TreeModel plain = tube({0.0f, 0.0f});
  plain.bark_texture = plain.bark_normal = Image8{};
  plain.bark_color = {0.1f, 0.4f, 0.1f};
  const glm::vec3 green = render(plain, sun);
  EXPECT_GT(green.g, 2.0f * green.r);
}
