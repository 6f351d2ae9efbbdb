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

void place_twig_leaves(TreeGraph& graph, const LeafParams& params, uint64_t seed) {
  const size_t n = graph.nodes.size();
  if (n < 2) return;
  auto children = children_of(graph);
  // single_path[i]: the subtree of i is one chain ending in a tip. Children have larger
  // indices, so a reverse sweep sees them first.
  std::vector<char> single_path(n, 0);
  for (size_t k = n; k-- > 0;)
    single_path[k] = children[k].empty() || (children[k].size() == 1 && single_path[children[k][0]]);
  auto bears_leaves = [&](size_t i) { return i > 0 && graph.nodes[i].parent >= 0 && single_path[i]; };

  // The point z inside the crown that blades face away from.
  glm::vec3 centroid(0.0f);
  float lo = INFINITY, hi = -INFINITY;
  size_t count = 0;
  for (size_t i = 0; i < n; ++i)
    if (bears_leaves(i)) {
      centroid += graph.nodes[i].position;
      lo = std::min(lo, graph.nodes[i].position.y);
      hi = std::max(hi, graph.nodes[i].position.y);
      ++count;
    }
  if (count == 0) return;
  centroid /= float(count);
  const glm::vec3 inside = centroid - glm::vec3(0.0f, 0.25f * (hi - lo), 0.0f);

  Rng rng(seed, /*stream=*/3);
  const float tilt0 = params.angle_deg * float(kPi) / 180.0f;
  const float tilt_jitter = params.angle_jitter_deg * float(kPi) / 180.0f;
  const double divergence = double(params.divergence_deg) * kPi / 180.0;
  const int per_node = leaves_at_node(params.phyllotaxis, params.per_node);
  auto add = [&](glm::vec3 pos, glm::vec3 axis, glm::vec3 reference, double azimuth) {
    float tilt = tilt0 + tilt_jitter * float(rng.symmetric());
    float size = params.size * float(1.0 + double(params.size_jitter) * rng.symmetric());
    glm::vec3 facing = pos - inside;
    facing = glm::length(facing) > 1e-6f ? glm::normalize(facing) : glm::vec3(0, 1, 0);
    LeafPlacement leaf = orient_leaf(pos, axis, float(azimuth), tilt, facing, size, reference);
    leaf.color = leaf_color_variation(rng, params.color_jitter);
    graph.leaves.push_back(leaf);
  };

  // Per node of a twig: its segment direction, transported reference, phyllotaxis phase and
  // the count of leaf nodes so far (parents come first).
  std::vector<glm::vec3> axis_of(n, glm::vec3(0.0f)), ref_of(n, glm::vec3(0.0f));
  std::vector<double> phase_of(n, 0.0);
  std::vector<long> nodes_of(n, 0);
  for (size_t i = 1; i < n; ++i) {
    if (!bears_leaves(i)) continue;
    const TreeNode& node = graph.nodes[i];
    const size_t parent = size_t(node.parent);
    glm::vec3 from = graph.nodes[parent].position;
    glm::vec3 seg = node.position - from;
    glm::vec3 axis = glm::length(seg) > 1e-12f ? glm::normalize(seg) : glm::vec3(0, 1, 0);
    if (bears_leaves(parent)) {  // the twig goes on: carry its frame and phase
      ref_of[i] = transport(ref_of[parent], axis_of[parent], axis);
      phase_of[i] = phase_of[parent];
      nodes_of[i] = nodes_of[parent];
    } else {  // a twig starts: random phase
      ref_of[i] = any_perpendicular(axis);
      phase_of[i] = rng.uniform(0.0, 2.0 * kPi);
    }
    axis_of[i] = axis;
    const bool tip = children[i].empty();
    const int leaf_nodes = tip ? params.along - 1 : params.along;
    for (int m = 1; m <= leaf_nodes; ++m) {
      glm::vec3 pos = m == params.along ? node.position
                                        : from + seg * (float(m) / float(std::max(params.along, 1)));
      for (int j = 0; j < per_node; ++j)
        add(pos, axis, ref_of[i],
            phase_of[i] + phyllotaxis_azimuth(params.phyllotaxis, per_node, nodes_of[i], j, divergence));
      ++nodes_of[i];
    }
    if (tip) {
      // The tip cluster: spread evenly around the twig, from a random start.
      double start = rng.uniform(0.0, 2.0 * kPi);
      for (int k = 0; k < params.per_tip; ++k)
        add(node.position, axis, ref_of[i], start + 2.0 * kPi * double(k) / double(params.per_tip));
    }
  }
}

}  // namespace forest
