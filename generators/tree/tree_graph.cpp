#include "generators/tree/tree_graph.h"

namespace forest {

std::vector<std::vector<uint32_t>> children_of(const TreeGraph& graph) {
  std::vector<std::vector<uint32_t>> children(graph.nodes.size());
  for (size_t i = 0; i < graph.nodes.size(); ++i) {
    int32_t p = graph.nodes[i].parent;
    // The graph invariant (parent < own index) makes this a forest rooted at the nodes with
    // parent -1; anything else is ignored rather than trusted to index the array.
    if (p >= 0 && size_t(p) < i) children[size_t(p)].push_back(uint32_t(i));
  }
  return children;
}

}  // namespace forest
