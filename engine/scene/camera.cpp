#include "engine/scene/camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace forest {

CameraMatrices camera_matrices(const CameraDesc& camera, float aspect) {
  CameraMatrices m;
  m.position = camera.position;
  m.forward = glm::normalize(camera.target - camera.position);
  // Looking straight up or down: pick another up vector so lookAt stays defined.
  glm::vec3 up = std::abs(m.forward.y) > 0.999f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  m.view = glm::lookAt(camera.position, camera.target, up);
  m.proj = glm::mat4(0.0f);
  if (camera.ortho_height > 0.0f) {
    // Orthographic, reversed Z over [near, far]: depth = (far + z_view) / (far − near).
    float h = 2.0f / camera.ortho_height, range = std::max(camera.far - camera.near, 1e-6f);
    m.proj[0][0] = h / aspect;
    m.proj[1][1] = -h;
    m.proj[2][2] = 1.0f / range;
    m.proj[3][2] = camera.far / range;
    m.proj[3][3] = 1.0f;
  } else {
    float f = 1.0f / std::tan(glm::radians(camera.fov_deg) * 0.5f);
    m.proj[0][0] = f / aspect;
    m.proj[1][1] = -f;  // Vulkan's framebuffer y points down
    m.proj[2][3] = -1.0f;
    m.proj[3][2] = camera.near;
  }
  if (camera.ndc_offset != glm::vec2(0.0f)) {  // clip += offset · w: the same shift in NDC at every depth
    glm::mat4 shift(1.0f);
    shift[3][0] = camera.ndc_offset.x;
    shift[3][1] = camera.ndc_offset.y;
    m.proj = shift * m.proj;
  }
  m.view_proj = m.proj * m.view;

  // Gribb-Hartmann on the rows of view_proj (Vulkan clip: -w<=x,y<=w, 0<=z<=w).
  auto row = [&](int i) { return glm::vec4(m.view_proj[0][i], m.view_proj[1][i], m.view_proj[2][i], m.view_proj[3][i]); };
  glm::vec4 planes[5] = {row(3) + row(0), row(3) - row(0), row(3) + row(1), row(3) - row(1), row(3) - row(2)};
  for (int i = 0; i < 5; ++i) m.frustum[size_t(i)] = planes[i] / glm::length(glm::vec3(planes[i]));
  m.frustum[5] = glm::vec4(-m.forward, glm::dot(m.forward, camera.position) + camera.far);
  return m;
}

glm::vec3 project_to_pixel(const CameraMatrices& m, glm::vec3 world, float width, float height) {
  glm::vec4 c = m.view_proj * glm::vec4(world, 1.0f);
  glm::vec3 ndc = glm::vec3(c) / c.w;
  return {(ndc.x * 0.5f + 0.5f) * width, (ndc.y * 0.5f + 0.5f) * height, ndc.z};
}

}  // namespace forest
