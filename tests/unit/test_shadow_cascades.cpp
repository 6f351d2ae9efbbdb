// The sun's shadow cascades (engine/render/shadow_cascades.h): they cover the view out to the
// shadow distance, hold every caster between the sun and the view, and are stable: moving the
// camera slides each cascade by whole texels, turning it changes no cascade's size.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/render/shadow_cascades.h"

using namespace forest;

namespace {

const ShadowBounds kBounds{{-200.0f, -5.0f, -200.0f}, {200.0f, 40.0f, 200.0f}};
const glm::vec3 kSun = glm::normalize(glm::vec3(0.45f, 0.75f, 0.35f));

CameraDesc camera_at(glm::vec3 position, glm::vec3 forward) {
  CameraDesc c;
  c.position = position;
  c.target = position + forward;
  c.fov_deg = 50.0f;
  c.near = 0.1f;
  return c;
}

// Texel coordinates of a world point in cascade c.
glm::vec2 texel_of(const ShadowCascade& c, glm::vec3 p, float resolution) {
  glm::vec4 q = c.view_proj * glm::vec4(p, 1.0f);
  return (glm::vec2(q) * 0.5f + 0.5f) * resolution;
}

}  // namespace

TEST(ShadowCascades, SplitsGrowToTheShadowDistance) {
  ShadowCascades s = compute_shadow_cascades(camera_at({0, 10, 0}, {0, -0.2f, 1}), 16.0f / 9.0f, kSun, 150.0f, 2048, kBounds);
  float previous = 0.0f;
  for (const ShadowCascade& c : s.cascades) {
    EXPECT_GT(c.split_far, previous);
    EXPECT_GT(c.texel, 0.0f);
    previous = c.split_far;
  }
  EXPECT_FLOAT_EQ(s.cascades.back().split_far, 150.0f);
  // Nearer cascades are sharper.
  EXPECT_LT(s.cascades[0].texel, s.cascades[1].texel);
  EXPECT_LT(s.cascades[1].texel, s.cascades[2].texel);
}

TEST(ShadowCascades, EveryViewPointIsInsideItsCascadeAndEveryCasterTowardTheSunToo) {
  CameraDesc cam = camera_at({3, 12, -7}, {0.3f, -0.25f, 1});
  const float aspect = 16.0f / 9.0f;
  ShadowCascades s = compute_shadow_cascades(cam, aspect, kSun, 150.0f, 1024, kBounds);
  CameraMatrices cm = camera_matrices(cam, aspect);
  glm::vec3 right = glm::normalize(glm::cross(cm.forward, glm::vec3(0, 1, 0)));
  glm::vec3 up = glm::cross(right, cm.forward);
  float t = std::tan(glm::radians(cam.fov_deg) * 0.5f);
  int checked = 0;
  for (float depth = 1.0f; depth < 150.0f; depth *= 1.3f)
    for (float sx = -1.0f; sx <= 1.0f; sx += 0.5f)
      for (float sy = -1.0f; sy <= 1.0f; sy += 0.5f) {
        glm::vec3 p = cam.position + cm.forward * depth + right * (sx * t * aspect * depth) + up * (sy * t * depth);
        uint32_t c = depth < s.cascades[0].split_far ? 0 : depth < s.cascades[1].split_far ? 1 : 2;
        for (float lift : {0.0f, 20.0f}) {  // the point, and a caster 20 m toward the sun from it
          glm::vec3 q = p + kSun * lift;
          if (q.y > kBounds.max.y) continue;
          glm::vec4 clip = s.cascades[c].view_proj * glm::vec4(q, 1.0f);
          EXPECT_LE(std::abs(clip.x), 1.0f) << "depth " << depth << " lift " << lift;
          EXPECT_LE(std::abs(clip.y), 1.0f) << "depth " << depth << " lift " << lift;
          EXPECT_GE(clip.z, 0.0f) << "depth " << depth << " lift " << lift;
          EXPECT_LE(clip.z, 1.0f) << "depth " << depth << " lift " << lift;
          for (const glm::vec4& plane : s.cascades[c].planes)  // the cull keeps it as a caster
            EXPECT_GE(glm::dot(glm::vec3(plane), q) + plane.w, 0.0f) << "depth " << depth << " lift " << lift;
          if (lift > 0.0f) {  // the caster is nearer the sun than the point it shades
            glm::vec4 at = s.cascades[c].view_proj * glm::vec4(p, 1.0f);
            EXPECT_LT(clip.z, at.z);
          }
          ++checked;
        }
      }
  EXPECT_GT(checked, 200);
}

// The caster volume is tighter than the map: trees beside the view slice, which shade no
// receiver of it, are not drawn.
TEST(ShadowCascades, CastersBesideTheViewAreCulled) {
  CameraDesc cam = camera_at({0, 10, 0}, {0, -0.1f, 1});
  ShadowCascades s = compute_shadow_cascades(cam, 1.5f, kSun, 150.0f, 2048, kBounds);
  for (size_t c = 0; c < s.cascades.size(); ++c) {
    const ShadowCascade& sc = s.cascades[c];
    // Ground points the map covers: how many of them the cull keeps as casters.
    size_t covered = 0, kept = 0;
    for (float x = -1.5f; x <= 1.5f; x += 0.02f)
      for (float z = -1.5f; z <= 1.5f; z += 0.02f) {
        glm::vec3 p = sc.center + sc.radius * glm::vec3(x, 0.0f, z);
        p.y = 0.0f;
        glm::vec4 clip = sc.view_proj * glm::vec4(p, 1.0f);
        if (std::abs(clip.x) > 1.0f || std::abs(clip.y) > 1.0f) continue;
        ++covered;
        bool inside = true;
        for (const glm::vec4& plane : sc.planes) inside = inside && glm::dot(glm::vec3(plane), p) + plane.w >= 0.0f;
        kept += inside;
      }
    ASSERT_GT(covered, 1000u);
    EXPECT_LT(double(kept) / double(covered), 0.75) << "cascade " << c << ": " << kept << " of " << covered;
  }
}

TEST(ShadowCascades, MovingTheCameraSlidesEveryCascadeByWholeTexels) {
  const float resolution = 2048.0f;
  const glm::vec3 forward{0.2f, -0.3f, 1.0f};
  ShadowCascades a = compute_shadow_cascades(camera_at({0, 10, 0}, forward), 1.5f, kSun, 150.0f, 2048, kBounds);
  const glm::vec3 probe{13.7f, 2.1f, 40.3f};
  for (int step = 1; step <= 20; ++step) {
    glm::vec3 position = glm::vec3(0.1f * float(step), 10.0f + 0.03f * float(step), 0.07f * float(step));
    ShadowCascades b = compute_shadow_cascades(camera_at(position, forward), 1.5f, kSun, 150.0f, 2048, kBounds);
    for (size_t c = 0; c < a.cascades.size(); ++c) {
      EXPECT_FLOAT_EQ(a.cascades[c].radius, b.cascades[c].radius);
      glm::vec2 d = texel_of(b.cascades[c], probe, resolution) - texel_of(a.cascades[c], probe, resolution);
      // A world point lands on the same spot of a texel: the grid moved by whole texels.
      EXPECT_NEAR(d.x, std::round(d.x), 2e-3f) << "cascade " << c << " step " << step;
      EXPECT_NEAR(d.y, std::round(d.y), 2e-3f) << "cascade " << c << " step " << step;
    }
  }
}

TEST(ShadowCascades, TurningTheCameraKeepsEveryCascadesSize) {
  ShadowCascades a = compute_shadow_cascades(camera_at({0, 10, 0}, {0, -0.2f, 1}), 1.5f, kSun, 150.0f, 2048, kBounds);
  for (float yaw = 0.1f; yaw < 6.3f; yaw += 0.7f) {
    glm::vec3 forward{std::sin(yaw), -0.2f + 0.05f * std::cos(3.0f * yaw), std::cos(yaw)};
    ShadowCascades b = compute_shadow_cascades(camera_at({0, 10, 0}, forward), 1.5f, kSun, 150.0f, 2048, kBounds);
    for (size_t c = 0; c < a.cascades.size(); ++c) {
      EXPECT_FLOAT_EQ(a.cascades[c].radius, b.cascades[c].radius) << "cascade " << c << " yaw " << yaw;
      EXPECT_FLOAT_EQ(a.cascades[c].texel, b.cascades[c].texel);
    }
  }
}

// Without [render] shadow_resolution the cascades get twice the frame's height in texels,
// rounded up to a power of two: 720 p keeps 2048, 360 p gets 1024, and the size stays within
// [512, 4096].
TEST(ShadowCascades, ResolutionFollowsTheFrameHeight) {
  EXPECT_EQ(shadow_resolution_for(720), 2048u);
  EXPECT_EQ(shadow_resolution_for(360), 1024u);
  EXPECT_EQ(shadow_resolution_for(270), 1024u);
  EXPECT_EQ(shadow_resolution_for(1080), 4096u);
  EXPECT_EQ(shadow_resolution_for(64), 512u);
  EXPECT_EQ(shadow_resolution_for(5000), 4096u);
}
