#include "engine/scene/camera_path.h"

#include <algorithm>
#include <cmath>

namespace forest {

glm::vec3 centripetal_catmull_rom(glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec3 p3, float u) {
  // Knots t_i+1 = t_i + |p_i+1 − p_i|^α. Coincident points would give a zero interval (a
  // division by zero), so every interval is at least a tiny fraction of the middle one.
  auto step = [](glm::vec3 a, glm::vec3 b) { return std::sqrt(glm::length(b - a)); };
  float d12 = step(p1, p2);
  if (d12 < 1e-6f) return p1;  // the segment does not move
  float eps = 1e-4f * d12;
  float t0 = 0.0f, t1 = t0 + std::max(step(p0, p1), eps), t2 = t1 + d12, t3 = t2 + std::max(step(p2, p3), eps);
  float t = t1 + u * (t2 - t1);
  auto lerp = [](glm::vec3 a, glm::vec3 b, float ta, float tb, float tt) { return a * ((tb - tt) / (tb - ta)) + b * ((tt - ta) / (tb - ta)); };
  glm::vec3 a1 = lerp(p0, p1, t0, t1, t), a2 = lerp(p1, p2, t1, t2, t), a3 = lerp(p2, p3, t2, t3, t);
  glm::vec3 b1 = lerp(a1, a2, t0, t2, t), b2 = lerp(a2, a3, t1, t3, t);
  return lerp(b1, b2, t1, t2, t);
}

float path_duration(const CameraPath& path) {
  return path.keys.empty() ? 0.0f : path.keys.back().time - path.keys.front().time;
}

const CameraPath* find_path(const SceneDesc& scene, const std::string& name) {
  for (const CameraPath& p : scene.paths)
    if (p.name == name) return &p;
  return nullptr;
}

CameraDesc camera_at(const CameraPath& path, float t, const CameraDesc& base) {
  CameraDesc c = base;
  const std::vector<CameraKey>& k = path.keys;
  if (k.empty()) return c;
  const size_t n = k.size();
  float duration = path_duration(path);
  if (path.loop && duration > 0.0f) t = k.front().time + std::fmod(std::fmod(t - k.front().time, duration) + duration, duration);
  t = std::clamp(t, k.front().time, k.back().time);
  size_t i = 0;  // segment [i, i + 1] holds t
  while (i + 2 < n && t > k[i + 1].time) ++i;
  if (n == 1) {
    c.position = k[0].position, c.target = k[0].target, c.fov_deg = k[0].fov_deg;
    return c;
  }
  float span = k[i + 1].time - k[i].time;
  float u = span > 0.0f ? std::clamp((t - k[i].time) / span, 0.0f, 1.0f) : 1.0f;
  // Neighbours: wrap on a loop (whose last key repeats the first), else mirror the end
  // point so the spline leaves the first and reaches the last key along the chord.
  auto neighbour = [&](long j, glm::vec3 CameraKey::*field) -> glm::vec3 {
    if (j >= 0 && j < long(n)) return k[size_t(j)].*field;
    if (path.loop && n > 2) return k[size_t(j < 0 ? long(n) - 2 : 1)].*field;
    if (j < 0) return 2.0f * (k[0].*field) - k[1].*field;
    return 2.0f * (k[n - 1].*field) - k[n - 2].*field;
  };
  long a = long(i);
  for (glm::vec3 CameraKey::*field : {&CameraKey::position, &CameraKey::target}) {
    glm::vec3 v = centripetal_catmull_rom(neighbour(a - 1, field), neighbour(a, field), neighbour(a + 1, field),
                                          neighbour(a + 2, field), u);
    (field == &CameraKey::position ? c.position : c.target) = v;
  }
  c.fov_deg = k[i].fov_deg + (k[i + 1].fov_deg - k[i].fov_deg) * u;
  // A target that meets the eye has no direction: keep looking along the path's chord.
  if (glm::length(c.target - c.position) < 1e-4f) c.target = c.position + (k[i + 1].target - k[i].position);
  return c;
}

}  // namespace forest
