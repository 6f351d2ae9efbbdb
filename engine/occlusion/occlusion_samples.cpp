#include "engine/occlusion/occlusion_samples.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace forest {

namespace {

// The metaball hull is blobby: a sample in a dent faces the camera yet hides behind the bumps
// around it, which hold leaves of the same tree. Moving samples this many metaball radii
// toward the camera clears the bumps, while trees a few meters apart still hide each other.
constexpr float kHullMarginRadii = 2.0f;

// Does the ray from p along n leave the mesh without hitting it again (Möller–Trumbore)?
bool ray_escapes(const Mesh& mesh, glm::vec3 p, glm::vec3 n) {
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    glm::vec3 a = mesh.vertices[mesh.indices[t]].position, b = mesh.vertices[mesh.indices[t + 1]].position,
              c = mesh.vertices[mesh.indices[t + 2]].position;
    glm::vec3 e1 = b - a, e2 = c - a, q = glm::cross(n, e2);
    float det = glm::dot(e1, q);
    if (std::abs(det) < 1e-12f) continue;
    glm::vec3 s = p - a;
    float u = glm::dot(s, q) / det;
    if (u < 0.0f || u > 1.0f) continue;
    glm::vec3 r = glm::cross(s, e1);
    float v = glm::dot(n, r) / det;
    if (v < 0.0f || u + v > 1.0f) continue;
    if (glm::dot(e2, r) / det > 0.0f) return false;
  }
  return true;
}

}  // namespace

OcclusionSamples occlusion_samples(const TreeModel& model) {
  OcclusionSamples out;
  if (const std::optional<HullSamples>& hull = model.bake.hull) {
    // Checked when the asset was read (bake_from_json); here only what would read out of bounds.
    if (hull->normals.size() != hull->points.size())
      throw std::invalid_argument("occlusion_samples: " + std::to_string(hull->normals.size()) + " normals for " +
                                  std::to_string(hull->points.size()) + " hull samples");
    for (size_t i = 0; i < hull->points.size(); ++i) {
      glm::vec3 n = hull->normals[i];
      float len = glm::length(n);
      if (!(len > 1e-6f)) throw std::invalid_argument("occlusion_samples: zero normal of hull sample " + std::to_string(i));
      out.samples.push_back({glm::vec4(hull->points[i], 1.0f), glm::vec4(n / len, 0.0f)});
    }
    float r = hull->radius;
    out.margin = kHullMarginRadii * (std::isfinite(r) && r > 0.0f ? r : 0.05f * model.bounding_sphere.w);
    // A crown whose leaves line a shell has a hollow hull: its inner surface, and deep pits,
    // are hidden by the tree's own foliage from every side, so samples there would read as
    // occluded for a tree in plain view. Keep the samples from which the outward ray escapes.
    if (!model.hull.indices.empty()) {
      const float offset = 1e-3f * std::max(model.bounding_sphere.w, 1e-3f);
      glm::vec3 lo(1e30f), hi(-1e30f);
      for (const Vertex& v : model.hull.vertices) lo = glm::min(lo, v.position), hi = glm::max(hi, v.position);
      const glm::vec3 centre = 0.5f * (lo + hi);
      std::vector<gpu::HullSample> outer;
      for (const gpu::HullSample& h : out.samples) {
        glm::vec3 p(h.position), n(h.normal), radial = p - centre;
        if (glm::length(radial) < 1e-6f) continue;
        radial = glm::normalize(radial);
        // Outward along its normal and away from the hull's centre: on the outer shell.
        if (ray_escapes(model.hull, p + offset * n, n) && ray_escapes(model.hull, p + offset * radial, radial))
          outer.push_back(h);
      }
      if (outer.size() >= out.samples.size() / 4) out.samples = std::move(outer);
    }
    out.from_hull = !out.samples.empty();
    if (out.from_hull) return out;
  }
  // Not baked: an ellipsoid spanning the leaves' bounding box (the crown), or the bounding
  // sphere for a leafless model, sampled at Fibonacci-spiral directions (deterministic).
  glm::vec3 center(model.bounding_sphere), axes(model.bounding_sphere.w);
  if (!model.leaves.empty()) {
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const LeafPlacement& l : model.leaves) lo = glm::min(lo, l.position), hi = glm::max(hi, l.position);
    center = 0.5f * (lo + hi);
    axes = glm::max(0.5f * (hi - lo), glm::vec3(0.05f * model.bounding_sphere.w));
  }
  const float golden = 2.39996323f;  // π (3 − √5)
  for (uint32_t i = 0; i < kEllipsoidOcclusionSamples; ++i) {
    float y = 1.0f - 2.0f * (float(i) + 0.5f) / float(kEllipsoidOcclusionSamples);
    float ring = std::sqrt(std::max(0.0f, 1.0f - y * y));
    glm::vec3 d(ring * std::cos(golden * float(i)), y, ring * std::sin(golden * float(i)));
    out.samples.push_back({glm::vec4(center + axes * d, 1.0f), glm::vec4(glm::normalize(d / axes), 0.0f)});
  }
  out.margin = 0.1f * glm::min(axes.x, glm::min(axes.y, axes.z)) + 0.02f * model.bounding_sphere.w;
  return out;
}

}  // namespace forest
