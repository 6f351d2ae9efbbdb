// The skeleton every modeling method produces: all randomness of a tree lives here;
// meshing is a pure function of it.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace forest {

struct TreeNode {
  glm::vec3 position{0.0f};  // model space, meters, +Y up, root at the origin
  float radius = 0.0f;       // branch radius at this node, meters
  int32_t parent = -1;       // index of the parent node, -1 for the root; parent < own index
  uint32_t order = 0;        // branching order: 0 trunk, 1 first-order branches, ...
};

// Where a leaf card is attached: the card's local +Y points along the blade,
// its local +Z is the blade's normal.
struct LeafPlacement {
  glm::vec3 position{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // w, x, y, z (glm order)
  float scale = 1.0f;                           // blade length, meters
  glm::vec3 color{1.0f};                        // per-leaf multiplier of the model's leaf color
};

struct TreeGraph {
  std::vector<TreeNode> nodes;           // nodes[0] is the root
  std::vector<LeafPlacement> leaves;
};

// Children lists, index-aligned with graph.nodes.
std::vector<std::vector<uint32_t>> children_of(const TreeGraph& graph);

}  // namespace forest
