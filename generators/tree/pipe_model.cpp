#include "generators/tree/pipe_model.h"

#include <cmath>

namespace forest {

void assign_pipe_radii(TreeGraph& graph, float tip_radius, float exponent) {
  const size_t n = graph.nodes.size();
  const double e = double(exponent);
  // sum[i] = sum over children c of r_c^e; parents come before children, so one reverse
  // sweep visits every child before its parent.
  std::vector<double> sum(n, 0.0);
  for (size_t k = n; k-- > 0;) {
    double r = sum[k] > 0.0 ? std::pow(sum[k], 1.0 / e) : double(tip_radius);
    graph.nodes[k].radius = float(r);
    int32_t p = graph.nodes[k].parent;
    if (p >= 0 && size_t(p) < k) sum[size_t(p)] += std::pow(r, e);
  }
}

}  // namespace forest
