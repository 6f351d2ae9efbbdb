// The CPU parts of the leaf coverage measurement (engine/tools/measure/leaf_coverage.h): the
// mask's pixel hull, the fitted orthographic camera, and the orthographic projection
// (engine/scene/camera.h) it renders with.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/scene/camera.h"
#include "engine/tools/measure/leaf_coverage.h"

using namespace forest;

namespace {

FrameImage blank(uint32_t w, uint32_t h) {
  FrameImage f;
  f.width = w, f.height = h;
  f.rgba.assign(size_t(w) * h * 4, 0);
  for (size_t i = 3; i < f.rgba.size(); i += 4) f.rgba[i] = 255;
  return f;
}

void set(FrameImage& f, uint32_t x, uint32_t y) {
  uint8_t* p = &f.rgba[(size_t(y) * f.width + x) * 4];
  p[0] = p[1] = p[2] = 255;
}

}  // namespace

TEST(LeafCoverageMask, FilledRectangleIsOne) {
  FrameImage f = blank(64, 48);
  for (uint32_t y = 10; y < 30; ++y)
    for (uint32_t x = 5; x < 45; ++x) set(f, x, y);
  MaskCoverage m = mask_coverage(f);
  EXPECT_EQ(m.pixels, 800u);
  EXPECT_DOUBLE_EQ(m.hull_area, 800.0);
  EXPECT_DOUBLE_EQ(m.coverage(), 1.0);
  set(f, 63, 47);  // one stray pixel far away stretches the hull
  EXPECT_LT(mask_coverage(f).coverage(), 0.75);
}

TEST(LeafCoverageMask, EmptyAndSinglePixel) {
  FrameImage f = blank(16, 16);
  EXPECT_EQ(mask_coverage(f).pixels, 0u);
  EXPECT_DOUBLE_EQ(mask_coverage(f).coverage(), 0.0);
  set(f, 3, 7);
  EXPECT_DOUBLE_EQ(mask_coverage(f).hull_area, 1.0);
  EXPECT_DOUBLE_EQ(mask_coverage(f).coverage(), 1.0);
}

TEST(LeafCoverageMask, CheckerboardAndDiagonal) {
  FrameImage f = blank(40, 40);
  for (uint32_t y = 0; y < 40; ++y)
    for (uint32_t x = 0; x < 40; ++x)
      if ((x + y) % 2 == 0) set(f, x, y);
  // The hull of the squares cuts the two corners without a pixel: (1600 − 1) square pixels.
  EXPECT_NEAR(mask_coverage(f).coverage(), 800.0 / 1599.0, 1e-12);
  // A diagonal line of n squares: the band |y − x| ≤ 1 in [0, n]², area 2n − 1.
  FrameImage d = blank(100, 100);
  for (uint32_t i = 0; i < 100; ++i) set(d, i, i);
  EXPECT_DOUBLE_EQ(mask_coverage(d).hull_area, 199.0);
  EXPECT_NEAR(mask_coverage(d).coverage(), 100.0 / 199.0, 1e-12);
}

TEST(LeafCoverageCamera, OrthographicProjectionIgnoresDistance) {
  CameraDesc cam;
  cam.position = {0.0f, 5.0f, -20.0f};
  cam.target = {0.0f, 5.0f, 0.0f};
  cam.near = 2.0f;
  cam.far = 40.0f;
  cam.ortho_height = 10.0f;
  CameraMatrices m = camera_matrices(cam, 2.0f);
  for (float z : {-15.0f, 0.0f, 15.0f}) {
    // 5 m up from the axis is the top edge, 10 m to the side (aspect 2) the side edge, at any depth.
    glm::vec3 top = project_to_pixel(m, {0.0f, 10.0f, z}, 200.0f, 100.0f);
    glm::vec3 side = project_to_pixel(m, {-10.0f, 5.0f, z}, 200.0f, 100.0f);
    EXPECT_NEAR(top.y, 0.0f, 1e-3f);
    EXPECT_NEAR(top.x, 100.0f, 1e-3f);
    EXPECT_NEAR(std::min(side.x, 200.0f - side.x), 0.0f, 1e-3f);
  }
  // Reversed Z, linear: 1 at the near plane, 0 at the far plane.
  EXPECT_NEAR(project_to_pixel(m, {0.0f, 5.0f, -18.0f}, 200.0f, 100.0f).z, 1.0f, 1e-5f);
  EXPECT_NEAR(project_to_pixel(m, {0.0f, 5.0f, 20.0f}, 200.0f, 100.0f).z, 0.0f, 1e-5f);
  EXPECT_NEAR(project_to_pixel(m, {0.0f, 5.0f, 1.0f}, 200.0f, 100.0f).z, 0.5f, 1e-5f);
  // Frustum: inside between near and far, outside beyond the frame.
  auto inside = [&](glm::vec3 p) {
    for (glm::vec4 pl : m.frustum)
      if (glm::dot(glm::vec3(pl), p) + pl.w < 0.0f) return false;
    return true;
  };
  EXPECT_TRUE(inside({9.0f, 9.0f, 10.0f}));
  EXPECT_FALSE(inside({11.0f, 5.0f, 0.0f}));
  EXPECT_FALSE(inside({0.0f, 10.5f, 0.0f}));
  EXPECT_FALSE(inside({0.0f, 5.0f, -19.0f}));  // before the near plane
}

TEST(LeafCoverageCamera, FittedSideCameraFramesTheBox) {
  Box box{{-1.0f, 0.0f, -3.0f}, {3.0f, 10.0f, 1.0f}};
  for (float azimuth : {0.0f, 90.0f, 180.0f, 270.0f}) {
    CameraDesc cam = fitted_side_camera(box, glm::radians(azimuth), 0.1f);
    CameraMatrices m = camera_matrices(cam, 1.0f);
    glm::vec2 lo(1e9f), hi(-1e9f);
    for (int i = 0; i < 8; ++i) {
      glm::vec3 corner(i & 1 ? box.hi.x : box.lo.x, i & 2 ? box.hi.y : box.lo.y, i & 4 ? box.hi.z : box.lo.z);
      glm::vec3 p = project_to_pixel(m, corner, 1.0f, 1.0f);
      EXPECT_GT(p.z, 0.0f);
      EXPECT_LT(p.z, 1.0f);
      lo = glm::min(lo, glm::vec2(p)), hi = glm::max(hi, glm::vec2(p));
    }
    // The tall side (10 m) spans 1 / 1.1 of the frame, centred; the 4 m width less.
    EXPECT_NEAR(hi.y - lo.y, 1.0f / 1.1f, 1e-4f) << azimuth;
    EXPECT_NEAR(hi.x - lo.x, 0.4f / 1.1f, 1e-4f) << azimuth;
    EXPECT_NEAR(0.5f * (lo.x + hi.x), 0.5f, 1e-4f);
    EXPECT_NEAR(0.5f * (lo.y + hi.y), 0.5f, 1e-4f);
  }
  // From azimuth 90 the camera stands on +x and looks towards −x.
  CameraDesc east = fitted_side_camera(box, glm::radians(90.0f), 0.1f);
  EXPECT_GT(east.position.x, box.hi.x);
  EXPECT_NEAR(east.position.z, -1.0f, 1e-4f);
  // A wide, low box: the width sets the scale.
  CameraDesc wide = fitted_side_camera(Box{{-10.0f, 0.0f, -1.0f}, {10.0f, 2.0f, 1.0f}}, 0.0f, 0.0f);
  EXPECT_NEAR(wide.ortho_height, 20.0f, 1e-4f);
  EXPECT_NEAR(fitted_side_camera(Box{{-10.0f, 0.0f, -1.0f}, {10.0f, 2.0f, 1.0f}}, glm::radians(90.0f), 0.0f).ortho_height,
              2.0f, 1e-4f);
}
