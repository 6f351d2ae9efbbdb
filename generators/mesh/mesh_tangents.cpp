#include "generators/mesh/mesh_tangents.h"

#include <cmath>

namespace forest {

namespace {

glm::vec3 unit_normal(const Vertex& v) {
  float len = glm::length(v.normal);
  return len > 0.0f ? v.normal / len : glm::vec3(0.0f, 1.0f, 0.0f);
}

glm::vec3 perpendicular(glm::vec3 n) {
  glm::vec3 a = std::abs(n.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  return glm::normalize(glm::cross(n, a));
}

}  // namespace

std::vector<glm::vec4> mesh_tangents(const Mesh& mesh) {
  std::vector<glm::dvec3> du(mesh.vertices.size(), glm::dvec3(0.0)), dv(mesh.vertices.size(), glm::dvec3(0.0));
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const uint32_t i[3] = {mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
    const Vertex &a = mesh.vertices[i[0]], &b = mesh.vertices[i[1]], &c = mesh.vertices[i[2]];
    const glm::dvec3 e1(b.position - a.position), e2(c.position - a.position);
    const glm::dvec2 w1(b.uv - a.uv), w2(c.uv - a.uv);
    const double det = w1.x * w2.y - w2.x * w1.y;
    if (!(std::abs(det) > 1e-20)) continue;
    // dP/du and dP/dv of the triangle; summed unnormalized, so larger triangles (in uv, at
    // even texel density: in area) weigh more.
    const glm::dvec3 s = (e1 * w2.y - e2 * w1.y) / det, q = (e2 * w1.x - e1 * w2.x) / det;
    const double area = 0.5 * std::abs(det);
    for (uint32_t k : i) du[k] += s * area, dv[k] += q * area;
  }
  std::vector<glm::vec4> out(mesh.vertices.size());
  for (size_t k = 0; k < mesh.vertices.size(); ++k) {
    const glm::vec3 n = unit_normal(mesh.vertices[k]);
    glm::vec3 t = glm::vec3(du[k] - glm::dvec3(n) * glm::dot(glm::dvec3(n), du[k]));
    const float len = glm::length(t);
    if (!(len > 1e-12f) || !std::isfinite(len)) {
      out[k] = glm::vec4(perpendicular(n), 1.0f);
      continue;
    }
    t /= len;
    const float w = glm::dot(glm::dvec3(glm::cross(n, t)), dv[k]) <= 0.0 ? 1.0f : -1.0f;
    out[k] = glm::vec4(t, w);
  }
  return out;
}

}  // namespace forest
