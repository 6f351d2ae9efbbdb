// Camera matrices: right-handed view, +Y up, reversed-Z infinite perspective for Vulkan
// (depth 1 at the near plane, 0 at infinity: even precision over a kilometer of forest), or
// with CameraDesc::ortho_height an orthographic projection (measurements).
#pragma once
#include <array>
#include <cmath>

#include <glm/glm.hpp>

#include "engine/scene/scene_file.h"

namespace forest {

struct CameraMatrices {
  glm::mat4 view{1.0f};
  glm::mat4 proj{1.0f};
  glm::mat4 view_proj{1.0f};
  glm::vec3 position{0.0f};
  glm::vec3 forward{0.0f, 0.0f, -1.0f};
  // World-space planes, xyz inward unit normal, w offset: dot(n, p) + w >= 0 inside.
  // Order: left, right, bottom, top, near, far.
  std::array<glm::vec4, 6> frustum{};
};

CameraMatrices camera_matrices(const CameraDesc& camera, float aspect);

// A perspective frame's focal length in pixels, height / (2 tan(fov / 2)): a sphere of radius r
// at distance z (r << z) covers about 2 · r · focal_pixels / z pixels.
inline float focal_pixels(float height, float fov_deg) { return height / (2.0f * std::tan(glm::radians(fov_deg) * 0.5f)); }

// Clip-space projection of a world point to pixel coordinates (x right, y down); z = depth.
glm::vec3 project_to_pixel(const CameraMatrices& m, glm::vec3 world, float width, float height);

}  // namespace forest
