// Pure parts of `forest walk`: the fly camera's input handling and the HUD text panel.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/present/hud.h"
#include "engine/scene/fly_camera.h"

using namespace forest;

TEST(FlyCamera, StartsAsTheSceneCameraExactly) {
  CameraDesc scene;
  scene.position = {3.0f, 7.0f, -20.0f};
  scene.target = {1.0f, 5.0f, 4.0f};
  scene.fov_deg = 63.0f;
  FlyCamera c = fly_camera_from(scene);
  CameraDesc d = fly_camera_desc(c);
  EXPECT_EQ(d.position, scene.position);
  EXPECT_EQ(d.target, scene.target);
  EXPECT_EQ(d.fov_deg, 63.0f);
  glm::vec3 dir = glm::normalize(scene.target - scene.position);
  EXPECT_NEAR(glm::length(fly_forward(c) - dir), 0.0f, 1e-5f);
  fly_update(c, FlyInput{}, 1.0f, nullptr);  // no input: still the scene camera
  EXPECT_FALSE(c.moved);
}

TEST(FlyCamera, KeysMoveAlongViewAndRightAtSpeed) {
  CameraDesc scene;
  scene.position = {0.0f, 10.0f, 0.0f};
  scene.target = {0.0f, 10.0f, 5.0f};  // looking along +Z
  FlyCamera c = fly_camera_from(scene);
  c.speed = 4.0f;
  FlyInput in;
  in.forward = 1.0f;
  fly_update(c, in, 0.5f, nullptr);
  EXPECT_NEAR(c.position.z, 2.0f, 1e-5f);
  EXPECT_NEAR(c.position.x, 0.0f, 1e-5f);
  in = {};
  in.right = 1.0f;
  in.fast = true;
  fly_update(c, in, 0.5f, nullptr);
  // Right-handed, +Y up, looking along +Z: right is -X; shift is 4x.
  EXPECT_NEAR(c.position.x, -8.0f, 1e-4f);
  EXPECT_TRUE(c.moved);
  CameraDesc d = fly_camera_desc(c);
  EXPECT_NEAR(glm::length(glm::normalize(d.target - d.position) - fly_forward(c)), 0.0f, 1e-5f);
}

TEST(FlyCamera, MouseTurnsPitchClampsWheelScalesSpeed) {
  FlyCamera c = fly_camera_from(CameraDesc{});
  float yaw = c.yaw;
  FlyInput in;
  in.look_x = 100.0f;  // mouse right: turn right (yaw decreases toward -X)
  fly_update(c, in, 0.0f, nullptr);
  EXPECT_NEAR(c.yaw, yaw - 100.0f * kLookRadiansPerPixel, 1e-6f);
  in = {};
  in.look_y = -1e6f;  // far up: pitch stops short of vertical
  fly_update(c, in, 0.0f, nullptr);
  EXPECT_LT(c.pitch, 1.5708f);
  EXPECT_GT(c.pitch, 1.5f);
  float speed = c.speed;
  in = {};
  in.speed_steps = 2.0f;
  fly_update(c, in, 0.0f, nullptr);
  EXPECT_NEAR(c.speed, speed * kSpeedStep * kSpeedStep, 1e-4f);
}

TEST(FlyCamera, StaysAboveTheTerrain) {
  TerrainDesc td;
  td.size = 100.0f;
  td.resolution = 8;
  td.height = 20.0f;
  Terrain t = make_terrain(td);
  CameraDesc scene;
  scene.position = {0.0f, 50.0f, 0.0f};
  scene.target = {0.0f, 49.0f, 1.0f};
  FlyCamera c = fly_camera_from(scene);
  FlyInput in;
  in.up = -1.0f;
  c.speed = 1000.0f;
  fly_update(c, in, 1.0f, &t);
  EXPECT_NEAR(c.position.y, t.height_at(c.position.x, c.position.z) + kEyeAboveGround, 1e-3f);
}

TEST(Hud, PanelSizeFollowsTextAndScale) {
  uint32_t w1, h1, w2, h2, w3, h3;
  text_panel_size({"fps 60"}, 1, &w1, &h1);
  text_panel_size({"fps 60 and a longer line"}, 1, &w2, &h2);
  text_panel_size({"fps 60", "two"}, 2, &w3, &h3);
  EXPECT_GT(w2, w1);
  EXPECT_EQ(h2, h1);
  EXPECT_EQ(w3, 2 * w1);
  EXPECT_GT(h3, 2 * h1);
  uint32_t w0, h0;
  text_panel_size({}, 1, &w0, &h0);
  EXPECT_EQ(w0 * h0, 0u);
}

TEST(Hud, TextIsDrawnInTheRequestedByteOrder) {
  OverlayImage rgba = draw_text_panel({"Ab 12.5 ms"}, 1, false);
  OverlayImage bgra = draw_text_panel({"Ab 12.5 ms"}, 1, true);
  ASSERT_EQ(rgba.bytes.size(), size_t(rgba.width) * rgba.height * 4);
  ASSERT_EQ(rgba.bytes.size(), bgra.bytes.size());
  size_t text = 0, background = 0;
  for (size_t i = 0; i < rgba.bytes.size(); i += 4) {
    EXPECT_EQ(rgba.bytes[i], bgra.bytes[i + 2]);
    EXPECT_EQ(rgba.bytes[i + 1], bgra.bytes[i + 1]);
    EXPECT_EQ(rgba.bytes[i + 3], 255);
    if (rgba.bytes[i] > 200) ++text;
    else if (rgba.bytes[i] < 40) ++background;
  }
  EXPECT_GT(text, 30u);                 // strokes of 9 glyphs
  EXPECT_GT(background, text);          // mostly panel
  EXPECT_EQ(text + background, rgba.bytes.size() / 4);
  // Empty text: only the panel.
  OverlayImage blank = draw_text_panel({"          "}, 1, false);
  for (size_t i = 0; i < blank.bytes.size(); i += 4) EXPECT_LT(blank.bytes[i], 40);
}
