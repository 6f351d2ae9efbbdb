#include "generators/tree/leaves.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "generators/mesh/frames.h"

namespace forest {

namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

std::optional<Phyllotaxis> parse_phyllotaxis(std::string_view name) {
  if (name == "alternate" || name == "distichous") return Phyllotaxis::alternate;
  if (name == "opposite" || name == "decussate") return Phyllotaxis::opposite;
  if (name == "whorled") return Phyllotaxis::whorled;
  if (name == "spiral") return Phyllotaxis::spiral;
  return std::nullopt;
}

const char* phyllotaxis_name(Phyllotaxis mode) {
  switch (mode) {
    case Phyllotaxis::alternate: return "alternate";
    case Phyllotaxis::opposite: return "opposite";
    case Phyllotaxis::whorled: return "whorled";
    case Phyllotaxis::spiral: return "spiral";
  }
  return "spiral";
}

int leaves_at_node(Phyllotaxis mode, int per_node) {
  switch (mode) {
    case Phyllotaxis::opposite: return 2;
    case Phyllotaxis::whorled: return std::max(3, per_node);
    default: return 1;
  }
}

double phyllotaxis_azimuth(Phyllotaxis mode, int per_node, long k, int j, double divergence) {
  const double kd = double(k);
  switch (mode) {
    case Phyllotaxis::alternate: return kd * kPi;
    case Phyllotaxis::opposite: return kd * 0.5 * kPi + double(j) * kPi;
    case Phyllotaxis::whorled: {
      double n = double(leaves_at_node(mode, per_node));
      return kd * kPi / n + double(j) * 2.0 * kPi / n;
    }
    case Phyllotaxis::spiral: return kd * divergence;
  }
  return 0.0;
}

LeafFrame leaf_frame_toward(glm::vec3 n_opt, glm::vec3 axis) {
  LeafFrame f;
  f.axis = glm::length(axis) > 1e-12f ? glm::normalize(axis) : glm::vec3(0.0f, 1.0f, 0.0f);
  glm::vec3 n = n_opt - glm::dot(n_opt, f.axis) * f.axis;
  f.normal = glm::length(n) > 1e-6f * std::max(1.0f, glm::length(n_opt)) ? glm::normalize(n)
                                                                          : any_perpendicular(f.axis);
  f.side = glm::cross(f.normal, f.axis);
  return f;
}

LeafFrame leaf_frame(glm::vec3 bud, glm::vec3 axis, glm::vec3 inside_point) {
  glm::vec3 n_opt = bud - inside_point;
  if (glm::length(n_opt) > 1e-12f) n_opt = glm::normalize(n_opt);
  return leaf_frame_toward(n_opt, axis);
}

glm::quat leaf_rotation(const LeafFrame& f) {
  return glm::normalize(glm::quat_cast(glm::mat3(-f.side, f.axis, f.normal)));
}

LeafPlacement orient_leaf(glm::vec3 position, glm::vec3 axis, float azimuth, float tilt,
                          glm::vec3 facing, float scale, glm::vec3 reference) {
  glm::vec3 a = glm::length(axis) > 1e-12f ? glm::normalize(axis) : glm::vec3(0, 1, 0);
  glm::vec3 p = reference - glm::dot(reference, a) * a;
  p = glm::length(p) > 1e-6f ? glm::normalize(p) : any_perpendicular(a);
  glm::vec3 q = glm::cross(a, p);
  glm::vec3 blade = glm::normalize(a * std::cos(tilt) +
                                   (p * std::cos(azimuth) + q * std::sin(azimuth)) * std::sin(tilt));
  LeafFrame f = leaf_frame_toward(facing, blade);
  // Facing along the blade itself: turn the normal toward the twig instead of anywhere.
  if (glm::length(facing - glm::dot(facing, blade) * blade) < 1e-4f * std::max(1.0f, glm::length(facing)))
    f = leaf_frame_toward(a, blade);
  LeafPlacement leaf;
  leaf.position = position;
  leaf.rotation = leaf_rotation(f);
  leaf.scale = scale;
  return leaf;
}

glm::vec3 leaf_color_variation(Rng& rng, float jitter) {
  if (!(jitter > 0.0f)) return glm::vec3(1.0f);
  float brightness = 1.0f + jitter * float(rng.symmetric());
  float yellow = jitter * float(rng.uniform());
  return brightness * glm::vec3(1.0f + 0.6f * yellow, 1.0f + 0.1f * yellow, 1.0f - 0.5f * yellow);
}

}  // namespace forest
