// TreeGraph -> triangle meshes: generalized cylinders along branch chains with
// rotation-minimizing frames (seed 000 ch5: parallel transport, Hanson 1995), the leaf card,
// and the bounding sphere. Pure functions: no randomness, same graph -> same mesh.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "generators/tree/tree_model.h"

namespace forest {

struct MesherParams {
  int min_sides = 3;   // ring sides of the thinnest chains
  int max_sides = 8;   // ring sides of the chain with the largest base radius (the trunk)
  // A node inside a chain gets no ring when the chain bends less than this there and its
  // radius differs from the last ring's by less than radius_tolerance (relative).
  float collinear_deg = 4.0f;
  float radius_tolerance = 0.02f;
  float min_radius = 1e-5f;  // radii below this are raised to it (no degenerate triangles)
};

// One ring of the tube mesh: vertices [first_vertex, first_vertex + sides] (the last one
// repeats the first position with u = 1, the texture seam). Exposed for tests and tools.
struct TubeRing {
  uint32_t node = 0;          // graph node at the ring center
  uint32_t chain = 0;         // chain index
  glm::vec3 center{0.0f};
  glm::vec3 tangent{0.0f, 1.0f, 0.0f};
  float radius = 0.0f;
  uint32_t sides = 0;
  uint32_t first_vertex = 0;
};

struct BranchMeshInfo {
  std::vector<TubeRing> rings;          // in chain order
  std::vector<uint32_t> cap_vertices;   // the apex vertex of each chain's tip cone
};

// Number of ring sides for a chain of base radius r, the trunk's being r_max.
int ring_sides(float r, float r_max, const MesherParams& params);

// Decomposes the graph into chains (a chain follows its thickest child; other children start
// new chains at their parent's position) and sweeps a ring along each. Every ring point is at
// distance radius from the ring center in the plane normal to the tangent; a cone closes each
// tip. u runs around the branch, v along it in units of the chain's base circumference.
Mesh mesh_branches(const TreeGraph& graph, const MesherParams& params = {},
                   BranchMeshInfo* info = nullptr);

// The leaf card in local space: a leaf-shaped hexagon (6 vertices, 4 triangles), blade from
// the origin along +Y to (0, 1, 0), normal +Z, counter-clockwise seen from +Z.
Mesh make_leaf_card();

// The transform of a leaf card vertex into model space.
glm::vec3 leaf_to_model(const LeafPlacement& leaf, glm::vec3 local);

// A sphere (xyz center, w radius) containing every branch vertex and every vertex of every
// placed leaf card: Ritter's approximation, then grown to include all points exactly, with a
// tiny margin against float rounding.
glm::vec4 bounding_sphere(const Mesh& branches, const Mesh& leaf_card,
                          const std::vector<LeafPlacement>& leaves);

}  // namespace forest
