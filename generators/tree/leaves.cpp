#include "generators/tree/leaves.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "generators/common/rng.h"

#include "generators/tree/frames.h"

namespace forest {

namespace {
constexpr float kPi = 3.14159265358979323846f;

}  // namespace

LeafPlacement orient_leaf(glm::vec3 position, glm::vec3 axis, float azimuth, float tilt,
                          glm::vec3 facing, float scale) {
  glm::vec3 a = glm::length(axis) > 1e-12f ? glm::normalize(axis) : glm::vec3(0, 1, 0);
  glm::vec3 p = any_perpendicular(a);
  glm::vec3 q = glm::cross(a, p);
  glm::vec3 y = glm::normalize(a * std::cos(tilt) +
                               (p * std::cos(azimuth) + q * std::sin(azimuth)) * std::sin(tilt));
  glm::vec3 n = facing - glm::dot(facing, y) * y;
  if (glm::length(n) < 1e-4f * std::max(1.0f, glm::length(facing))) n = a - glm::dot(a, y) * y;
  n = glm::length(n) < 1e-6f ? any_perpendicular(y) : glm::normalize(n);
  glm::vec3 x = glm::cross(y, n);  // right-handed card frame: x * y = n
  LeafPlacement leaf;
  leaf.position = position;
  leaf.rotation = glm::normalize(glm::quat_cast(glm::mat3(x, y, n)));
  leaf.scale = scale;
  return leaf;
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

  glm::vec3 centroid(0.0f);
  for (const TreeNode& node : graph.nodes) centroid += node.position;
  centroid /= float(n);

  Rng rng(seed, /*stream=*/3);
  const float tilt0 = params.angle_deg * kPi / 180.0f;
  const float tilt_jitter = params.angle_jitter_deg * kPi / 180.0f;
  auto add = [&](const TreeNode& node, glm::vec3 axis, float azimuth) {
    float tilt = tilt0 + tilt_jitter * float(rng.symmetric());
    float size = params.size * float(1.0 + double(params.size_jitter) * rng.symmetric());
    glm::vec3 facing = node.position - centroid;
    if (glm::length(facing) < 1e-6f) facing = glm::vec3(0, 1, 0);
    facing = glm::normalize(facing) + glm::vec3(0.0f, 0.5f, 0.0f);  // and a little skyward
    graph.leaves.push_back(orient_leaf(node.position, axis, azimuth, tilt, facing, size));
  };

  for (size_t i = 1; i < n; ++i) {
    const TreeNode& node = graph.nodes[i];
    if (node.parent < 0 || !single_path[i]) continue;
    glm::vec3 axis = node.position - graph.nodes[size_t(node.parent)].position;
    int count = children[i].empty() ? params.per_tip : params.along;
    // Spread the leaves of one node evenly around the twig, from a random start.
    float start = float(rng.uniform(0.0, 2.0 * kPi));
    for (int k = 0; k < count; ++k) add(node, axis, start + 2.0f * kPi * float(k) / float(count));
  }
}

}  // namespace forest
