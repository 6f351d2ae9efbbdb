// The fly camera of `forest walk`: position + yaw/pitch, moved by WASD-style input and
// mouse deltas, kept above the terrain. Pure functions so input handling is testable.
#pragma once
#include "engine/scene/scene_file.h"
#include "engine/scene/terrain.h"

namespace forest {

struct FlyCamera {
  glm::vec3 position{0.0f};
  float yaw = 0.0f;    // radians about +Y; 0 looks along +Z
  float pitch = 0.0f;  // radians, + looks up; kept within ±89°
  float speed = 15.0f; // meters per second
  CameraDesc lens;     // fov, near, far of the scene camera
  // Until the first move the camera is exactly the scene's (no round trip through angles),
  // so an untouched walk frame equals `forest render`'s frame.
  bool moved = false;
};

struct FlyInput {
  float forward = 0.0f, right = 0.0f, up = 0.0f;  // -1..1 each (keys held)
  float look_x = 0.0f, look_y = 0.0f;             // mouse motion, pixels (right, down)
  float speed_steps = 0.0f;                       // mouse wheel notches (+ faster)
  bool fast = false;                              // ×4 while held
};

constexpr float kLookRadiansPerPixel = 0.0025f;
constexpr float kSpeedStep = 1.25f;         // per wheel notch
constexpr float kEyeAboveGround = 1.7f;     // meters: the camera never goes below this

FlyCamera fly_camera_from(const CameraDesc& camera);
glm::vec3 fly_forward(const FlyCamera& camera);
// Advances by `seconds`; `terrain` (optional) keeps the eye above the ground.
void fly_update(FlyCamera& camera, const FlyInput& input, float seconds, const Terrain* terrain);
CameraDesc fly_camera_desc(const FlyCamera& camera);

}  // namespace forest
