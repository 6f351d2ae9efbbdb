// The Yao-8 graph (Xu 2015 ch3.2): from every node one directed edge to its nearest node in
// each of 8 sectors, so out-degree ≤ 8. The thesis does not define the 3D sectors; [ours]
// they are the octants of the offset q − p (sign of x, y, z; a zero component counts as +).
// Ties in distance go to the smaller index. Edges longer than `max_length` are dropped (a
// boundary node's empty octant would otherwise reach across the volume).
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace forest {

struct YaoGraph {
  std::vector<glm::vec3> positions;
  std::vector<uint32_t> offsets;  // size n + 1: out-edges of u are [offsets[u], offsets[u+1])
  std::vector<uint32_t> targets;
  std::vector<float> lengths;     // Euclidean edge lengths d_E
  size_t size() const { return positions.size(); }
};

// Octant index in [0, 8) of an offset vector.
inline int yao_sector(glm::vec3 d) {
  return (d.x >= 0.0f ? 1 : 0) | (d.y >= 0.0f ? 2 : 0) | (d.z >= 0.0f ? 4 : 0);
}

// Grid search that widens shell by shell and stops once every octant's nearest is final;
// two threads split the nodes (the result does not depend on the split).
YaoGraph build_yao8(std::vector<glm::vec3> positions, float max_length);

}  // namespace forest
