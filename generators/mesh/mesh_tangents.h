// Per-vertex tangents of a textured mesh for tangent-space normal maps (glTF TANGENT).
#pragma once
#include <vector>

#include <glm/glm.hpp>

#include "generators/model/tree_model.h"

namespace forest {

// xyz: the unit direction of increasing u in the vertex's tangent plane (the uv gradients of
// its triangles, summed; Lengyel 2001), w = ±1 such that cross(normal, xyz) · w points toward
// decreasing v, the +Y of a glTF normal map. A vertex whose triangles map no u direction
// (degenerate uv) gets any unit vector perpendicular to its normal, w = 1.
std::vector<glm::vec4> mesh_tangents(const Mesh& mesh);

}  // namespace forest
