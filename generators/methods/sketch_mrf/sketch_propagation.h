// Method `sketch-mrf`, part 3 (Neubert 2012 ch4.7): branch propagation by replication blocks.
// A replication block is a parent segment with its children, stored in the parent's frame
// and scaled by its length; copies are attached to open (childless) segments, inheriting the
// block's angles. Growth stops at the crown's surface of local revolution (a copy that
// crosses it is scaled back to touch it and stays closed) or after `generations`.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "generators/methods/sketch_mrf/sketch_mrf_inference.h"

namespace forest {

// Surface of revolution of a crown curve about the vertical axis x = axis_x: at height y the
// radius is the right half-width toward +x and the left half-width toward -x, interpolated
// by (1 +- cos phi) / 2 around the axis (phi = azimuth from +x).
struct CrownSurface {
  std::vector<glm::dvec2> polygon;  // closed curve (last point joins the first)
  double axis_x = 0.0;
  bool contains(glm::dvec3 p) const;
};

struct PropagationParams {
  int generations = 5;
  size_t max_segments = 30000;  // budget: propagation stops when the tree has this many
};

struct PropagatedTree {
  std::vector<glm::dvec3> position;  // node 0 = root; parent < index
  std::vector<int> parent;
  std::vector<uint32_t> order;       // lateral branchings from the trunk
  std::vector<char> sketched;        // 1 for nodes of the sketch
  size_t closed_by_crown = 0;        // copies scaled back to the crown surface
};

PropagatedTree propagate_branches(const SketchTree& tree, const SketchDepths& depths,
                                  const CrownSurface* crown, const PropagationParams& params,
                                  uint64_t seed);

}  // namespace forest
