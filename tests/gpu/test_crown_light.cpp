// Crown self-shadowing on the GPU (shaders/crown_light.h through leaf.vert and tree.frag): a
// low sun from +X darkens the far side of a baked broadleaf crown seen from straight above,
// for any instance rotation, and it is the baked depths that do it.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/render/renderer.h"
#include "engine/scene/camera.h"
#include "engine/scene/scene.h"
#include "generators/bake/hull/hull.h"
#include "generators/bake/hull/hull_depth.h"
#include "tests/gpu/gpu_scenes.h"
#include "tests/gpu/validated_gpu_test.h"

using namespace forest;
using namespace forest::test;

namespace {

constexpr uint32_t kSize = 256;

float linear(uint8_t v) {
  float c = float(v) / 255.0f;
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

TreeModel baked_broadleaf() {
  TreeModel m = broadleaf();
  Hull h = build_hull(m.leaves, plant_height(m));
  attach_hull(m, h);
  attach_crown_light(m, h);
  return m;
}

struct Halves {
  double near = 0, far = 0;  // mean luminance of leaf pixels, x > c + R/4 and x < c − R/4
  size_t near_n = 0, far_n = 0;
  double ratio() const { return far / near; }
};

class CrownShadowGpu : public ValidatedGpuTest {
 protected:
  // One tree at the origin, yaw `yaw_deg`, sun 10° above the horizon toward +X, an
  // orthographic camera straight above the crown; leaves alone (no bark), no shadows.
  Halves measure(const TreeModel& model, float yaw_deg) {
    SceneDesc desc = flat_ground(kSize, kSize, 100.0f);
    const float e = glm::radians(10.0f);
    desc.sky.sun_direction = glm::vec3(std::cos(e), std::sin(e), 0.0f);
    TreeDesc t;
    t.yaw_deg = yaw_deg;
    desc.trees = {t};
    Scene s = scene_of(std::move(desc), {model});
    // The crown's centre in world space: the bounding sphere turned by the instance's yaw.
    glm::vec3 c(model.bounding_sphere);
    const float radius = model.bounding_sphere.w;
    const glm::vec2 cs = s.instances[0].yaw_cos_sin;  // common.glsl rotate_yaw
    glm::vec3 world_c = glm::vec3(s.instances[0].position_scale) +
                        s.instances[0].position_scale.w * glm::vec3(cs.x * c.x + cs.y * c.z, c.y, -cs.y * c.x + cs.x * c.z);
    CameraDesc cam;
    cam.position = world_c + glm::vec3(0.0f, 3.0f * radius, 0.01f * radius);
    cam.target = world_c;
    cam.ortho_height = 2.2f * radius;
    cam.near = 0.1f;
    cam.far = 10.0f * radius;
    Renderer renderer(ctx_, s, kSize, kSize, 1);
    FrameSettings mask = scene_frame_settings(s.desc), shaded = mask;
    mask.mask = true;
    mask.branches = shaded.branches = false;
    FrameImage coverage, image;
    renderer.render(cam, &coverage, mask);
    renderer.render(cam, &image, shaded);
    // Where world x = c ± R/4 falls on the image (and which side +X is).
    CameraMatrices mats = camera_matrices(cam, 1.0f);
    float x_plus = project_to_pixel(mats, world_c + glm::vec3(0.25f * radius, 0, 0), float(kSize), float(kSize)).x;
    float x_minus = project_to_pixel(mats, world_c - glm::vec3(0.25f * radius, 0, 0), float(kSize), float(kSize)).x;
    Halves h;
    for (uint32_t y = 0; y < kSize; ++y)
      for (uint32_t x = 0; x < kSize; ++x) {
        if (coverage.pixel(x, y)[0] < 250) continue;  // not a leaf
        const uint8_t* p = image.pixel(x, y);
        double lum = 0.2126 * linear(p[0]) + 0.7152 * linear(p[1]) + 0.0722 * linear(p[2]);
        float px = float(x) + 0.5f;
        bool near_side = (px - x_plus) * (x_plus - x_minus) > 0.0f;
        bool far_side = (px - x_minus) * (x_minus - x_plus) > 0.0f;
        if (near_side) h.near += lum, ++h.near_n;
        if (far_side) h.far += lum, ++h.far_n;
      }
    EXPECT_GT(h.near_n, 500u);
    EXPECT_GT(h.far_n, 500u);
    h.near /= double(std::max<size_t>(h.near_n, 1));
    h.far /= double(std::max<size_t>(h.far_n, 1));
    return h;
  }
};

}  // namespace

TEST_F(CrownShadowGpu, LowSideSunDarkensTheFarSideAtAnyYaw) {
  TreeModel baked = baked_broadleaf();
  ASSERT_TRUE(baked.bake.crown.has_value());
  Halves h0 = measure(baked, 0.0f), h180 = measure(baked, 180.0f), h90 = measure(baked, 90.0f);
  // The same κ with every depth 0: what leaf orientation alone does.
  TreeModel flat = baked;
  for (CrownCube& d : flat.bake.crown->depths) d.fill(0.0f);
  Halves hz = measure(flat, 0.0f);
  // No crown depths (an asset baked before them): the bounding-sphere fallback.
  TreeModel unbaked = baked;
  unbaked.bake.crown.reset();
  Halves hf = measure(unbaked, 0.0f);
  std::printf("far/near: baked %.3f (yaw 0), %.3f (yaw 180), %.3f (yaw 90); zero depths %.3f; sphere fallback %.3f\n",
              h0.ratio(), h180.ratio(), h90.ratio(), hz.ratio(), hf.ratio());
  EXPECT_LE(h0.ratio(), 0.6);
  EXPECT_LE(h180.ratio(), 0.6);  // the sun is turned into model space: any rotation works
  EXPECT_LE(h90.ratio(), 0.6);
  EXPECT_GT(hz.ratio(), h0.ratio() + 0.1);  // it is the baked term that darkens the far side
  EXPECT_GT(hf.ratio(), h0.ratio());        // more than the sphere guess does
}
