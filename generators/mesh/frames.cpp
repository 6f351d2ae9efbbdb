#include "generators/mesh/frames.h"

#include <algorithm>

namespace forest {

glm::vec3 transport(glm::vec3 v, glm::vec3 from, glm::vec3 to) {
  glm::vec3 axis = glm::cross(from, to);
  float s = glm::length(axis);
  float c = glm::dot(from, to);
  if (s < 1e-7f) {
    if (c > 0.0f) return v;  // parallel: nothing turns
    return rotate_about(v, any_perpendicular(from), 3.14159265358979323846f);
  }
  return rotate_about(v, axis / s, std::atan2(s, c));
}

std::vector<Frame> parallel_transport(std::span<const glm::vec3> tangents, glm::vec3 normal0) {
  std::vector<Frame> frames;
  frames.reserve(tangents.size());
  glm::vec3 n = normal0;
  for (size_t i = 0; i < tangents.size(); ++i) {
    glm::vec3 t = tangents[i];
    if (i > 0) n = transport(n, frames.back().tangent, t);
    n -= glm::dot(n, t) * t;
    float len = glm::length(n);
    n = len > 1e-6f ? n / len : any_perpendicular(t);
    frames.push_back(Frame{t, n, glm::cross(t, n)});
  }
  return frames;
}

std::vector<Frame> parallel_transport_polyline(std::span<const glm::vec3> points, glm::vec3 normal0) {
  const size_t n = points.size();
  std::vector<glm::vec3> seg;  // unit direction of segment i (i -> i + 1), or zero
  for (size_t i = 0; i + 1 < n; ++i) {
    glm::vec3 d = points[i + 1] - points[i];
    float len = glm::length(d);
    seg.push_back(len > 1e-12f ? d / len : glm::vec3(0.0f));
  }
  std::vector<glm::vec3> tangents(n, glm::vec3(0.0f));
  for (size_t i = 0; i < n; ++i) {
    glm::vec3 in = i > 0 ? seg[i - 1] : glm::vec3(0.0f);
    glm::vec3 out = i + 1 < n ? seg[i] : glm::vec3(0.0f);
    glm::vec3 sum = in + out;
    float len = glm::length(sum);
    if (len > 1e-6f) tangents[i] = sum / len;
    else if (glm::length(out) > 0.0f) tangents[i] = out;  // a cusp: follow the way out
    else if (i > 0) tangents[i] = tangents[i - 1];
  }
  // Leading coincident points take the first real direction; none at all: +Y.
  auto first = std::find_if(tangents.begin(), tangents.end(), [](glm::vec3 t) { return t != glm::vec3(0.0f); });
  glm::vec3 fill = first == tangents.end() ? glm::vec3(0.0f, 1.0f, 0.0f) : *first;
  for (glm::vec3& t : tangents) {
    if (t != glm::vec3(0.0f)) break;
    t = fill;
  }
  return parallel_transport(tangents, normal0);
}

}  // namespace forest
