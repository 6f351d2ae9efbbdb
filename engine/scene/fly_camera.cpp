#include "engine/scene/fly_camera.h"

#include <algorithm>
#include <cmath>

namespace forest {

namespace {
constexpr float kMaxPitch = 1.5533f;  // 89°: lookAt stays defined
}

FlyCamera fly_camera_from(const CameraDesc& camera) {
  FlyCamera c;
  c.position = camera.position;
  c.lens = camera;
  glm::vec3 d = camera.target - camera.position;
  float len = glm::length(d);
  if (len > 0.0f) {
    d /= len;
    c.yaw = std::atan2(d.x, d.z);
    c.pitch = std::clamp(std::asin(std::clamp(d.y, -1.0f, 1.0f)), -kMaxPitch, kMaxPitch);
  }
  return c;
}

glm::vec3 fly_forward(const FlyCamera& c) {
  return {std::sin(c.yaw) * std::cos(c.pitch), std::sin(c.pitch), std::cos(c.yaw) * std::cos(c.pitch)};
}

void fly_update(FlyCamera& c, const FlyInput& in, float seconds, const Terrain* terrain) {
  if (in.speed_steps != 0.0f) c.speed = std::clamp(c.speed * std::pow(kSpeedStep, in.speed_steps), 0.5f, 2000.0f);
  bool look = in.look_x != 0.0f || in.look_y != 0.0f;
  bool move = in.forward != 0.0f || in.right != 0.0f || in.up != 0.0f;
  if (!look && !move) return;
  c.moved = true;
  // Mouse right turns right: with +Y up and yaw measured from +Z toward +X, that is -yaw.
  c.yaw -= in.look_x * kLookRadiansPerPixel;
  c.pitch = std::clamp(c.pitch - in.look_y * kLookRadiansPerPixel, -kMaxPitch, kMaxPitch);
  glm::vec3 forward = fly_forward(c);
  glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f)));
  float step = c.speed * (in.fast ? 4.0f : 1.0f) * seconds;
  c.position += (forward * in.forward + right * in.right + glm::vec3(0.0f, 1.0f, 0.0f) * in.up) * step;
  if (terrain) c.position.y = std::max(c.position.y, terrain->height_at(c.position.x, c.position.z) + kEyeAboveGround);
}

CameraDesc fly_camera_desc(const FlyCamera& c) {
  if (!c.moved) return c.lens;
  CameraDesc d = c.lens;
  d.position = c.position;
  d.target = c.position + fly_forward(c);
  return d;
}

}  // namespace forest
