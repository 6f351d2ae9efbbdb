#include "generators/tree/pipe_model.h"

#include <vector>

#include "generators/tree/allometry.h"

namespace forest {

void assign_pipe_radii(TreeGraph& graph, float tip_radius, float exponent) {
  auto children = children_of(graph);
  // Parents come before children, so one reverse sweep visits every child before its parent.
  std::vector<double> child_radii;
  for (size_t k = graph.nodes.size(); k-- > 0;) {
    child_radii.clear();
    for (uint32_t c : children[k]) child_radii.push_back(double(graph.nodes[c].radius));
    graph.nodes[k].radius = child_radii.empty()
                                ? tip_radius
                                : float(pipe_parent_radius(child_radii, double(exponent)));
  }
}

}  // namespace forest
