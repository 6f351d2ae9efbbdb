#include "engine/render/shadow_cascades.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace forest {

namespace {

// The eight corners of the camera's view volume between view depths zn and zf.
std::array<glm::vec3, 8> slice_corners(const CameraDesc& camera, float aspect, float zn, float zf) {
  glm::vec3 forward = glm::normalize(camera.target - camera.position);
  glm::vec3 up0 = std::abs(forward.y) > 0.999f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  glm::vec3 right = glm::normalize(glm::cross(forward, up0));
  glm::vec3 up = glm::cross(right, forward);
  std::array<glm::vec3, 8> corners;
  for (int i = 0; i < 8; ++i) {
    float z = i < 4 ? zn : zf;
    float half_h = camera.ortho_height > 0.0f ? camera.ortho_height * 0.5f
                                              : z * std::tan(glm::radians(camera.fov_deg) * 0.5f);
    float half_w = half_h * aspect;
    float sx = (i & 1) ? 1.0f : -1.0f, sy = (i & 2) ? 1.0f : -1.0f;
    corners[size_t(i)] = camera.position + forward * z + right * (sx * half_w) + up * (sy * half_h);
  }
  return corners;
}

// The sun camera's rotation: a function of the sun direction alone.
glm::mat4 sun_rotation(glm::vec3 sun) {
  glm::vec3 up = std::abs(sun.y) > 0.999f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  return glm::lookAt(glm::vec3(0.0f), -sun, up);
}

}  // namespace

uint32_t shadow_resolution_for(uint32_t height) {
  uint32_t r = 512;
  while (r < 2 * height && r < 4096) r *= 2;
  return r;
}

ShadowCascades compute_shadow_cascades(const CameraDesc& camera, float aspect, glm::vec3 sun, float distance,
                                       uint32_t resolution, const ShadowBounds& bounds) {
  ShadowCascades out;
  out.distance = distance;
  sun = glm::normalize(sun);
  const glm::mat4 rotation = sun_rotation(sun);
  const float zn0 = std::min(std::max(camera.near, kShadowSplitNear), distance * 0.5f);
  // Caster depth range along the sun: every corner of the bounds, in sun view space
  // (looking along −sun, so view z is negative in front).
  float bound_near = INFINITY, bound_far = -INFINITY;
  for (int i = 0; i < 8; ++i) {
    glm::vec3 c((i & 1) ? bounds.max.x : bounds.min.x, (i & 2) ? bounds.max.y : bounds.min.y,
                (i & 4) ? bounds.max.z : bounds.min.z);
    float z = -(rotation * glm::vec4(c, 1.0f)).z;  // distance in front of the sun camera
    bound_near = std::min(bound_near, z);
    bound_far = std::max(bound_far, z);
  }
  float zn = zn0;
  for (uint32_t c = 0; c < SHADOW_CASCADES; ++c) {
    float t = float(c + 1) / float(SHADOW_CASCADES);
    float zf = kShadowSplitLog * zn0 * std::pow(distance / zn0, t) + (1.0f - kShadowSplitLog) * (zn0 + (distance - zn0) * t);
    if (c + 1 == SHADOW_CASCADES) zf = distance;
    std::array<glm::vec3, 8> corners = slice_corners(camera, aspect, c == 0 ? 0.0f : zn, zf);
    glm::vec3 center(0.0f);
    for (const glm::vec3& p : corners) center += p * 0.125f;
    float radius = 0.0f;
    for (const glm::vec3& p : corners) radius = std::max(radius, glm::distance(p, center));
    // A radius that never changes with the camera's pose: rounded up to 1/16 m.
    radius = std::ceil(radius * 16.0f) / 16.0f;
    const float texel = 2.0f * radius / float(resolution);
    // Snap the centre to whole texels in the sun's frame.
    glm::vec3 ls = glm::vec3(rotation * glm::vec4(center, 1.0f));
    ls.x = std::floor(ls.x / texel) * texel;
    ls.y = std::floor(ls.y / texel) * texel;
    // Depth: from the nearest caster toward the sun to the far side of the sphere.
    float near = std::min(bound_near, -ls.z - radius) - 1.0f;
    float far = std::max(-ls.z + radius, near + 1.0f);
    glm::mat4 proj = glm::orthoRH_ZO(ls.x - radius, ls.x + radius, ls.y - radius, ls.y + radius, near, far);
    ShadowCascade& sc = out.cascades[c];
    sc.view_proj = proj * rotation;
    sc.split_far = zf;
    sc.texel = texel;
    sc.center = glm::vec3(glm::inverse(rotation) * glm::vec4(ls, 1.0f));
    sc.radius = radius;
    // Caster volume: only what can shade a receiver of this slice. The map covers the slice's
    // sphere (for stability), but a caster outside the slice's tight box in the sun's frame
    // (its corners' x, y extent, plus the PCF footprint) shades only texels no receiver of
    // this cascade reads; toward the sun it reaches the bounds, away from it the sphere's end.
    glm::vec2 lo(INFINITY), hi(-INFINITY);
    for (const glm::vec3& p : corners) {
      glm::vec3 q = glm::vec3(rotation * glm::vec4(p, 1.0f));
      lo = glm::min(lo, glm::vec2(q)), hi = glm::max(hi, glm::vec2(q));
    }
    lo -= glm::vec2(3.0f * texel), hi += glm::vec2(3.0f * texel);
    const glm::vec3 ax(rotation[0][0], rotation[1][0], rotation[2][0]);  // rows of the rotation
    const glm::vec3 ay(rotation[0][1], rotation[1][1], rotation[2][1]);
    const glm::vec3 az(rotation[0][2], rotation[1][2], rotation[2][2]);  // toward the sun
    sc.planes = {glm::vec4(ax, -lo.x), glm::vec4(-ax, hi.x), glm::vec4(ay, -lo.y), glm::vec4(-ay, hi.y),
                 glm::vec4(-az, -near), glm::vec4(az, far)};
    zn = zf;
  }
  return out;
}

}  // namespace forest
