// TreeGraph -> triangle meshes (Neubert 2012 ch5 "From graphs to models"): every branch chain's
// axis is a clamped cubic B-spline over its nodes (bspline.h), sampled adaptively to its
// curvature and swept by rings with parallel-transported frames (frames.h); at forks the
// branches are cut back to the bifurcation sphere (allometry.h) and joined by a junction
// surface, so that the branch mesh is closed except for the trunk's base ring. Also the leaf
// card and the bounding sphere. Pure functions: no randomness, same graph -> same mesh.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "generators/mesh/leaf_texture.h"
#include "generators/model/tree_model.h"

namespace forest {

struct MesherParams {
  int min_sides = 3;   // ring sides of the thinnest chains
  int max_sides = 8;   // ring sides of the chain with the largest base radius (the trunk)
  // Adaptive sampling of the axis splines: a new ring where the tangent has turned by more
  // than max_bend_deg since the last ring, or the radius changed by more than
  // radius_tolerance (relative).
  float max_bend_deg = 15.0f;
  float radius_tolerance = 0.25f;
  int spline_substeps = 8;   // dense samples per spline segment (node to node)
  float min_radius = 1e-5f;  // radii below this are raised to it (no degenerate triangles)
  // Forks. join_forks = false leaves every side branch as a tube closed at its start inside
  // its parent (no junction surfaces; the mesh is still closed, but interpenetrating).
  bool join_forks = true;
  // Angles between branches are clamped to [min, max] for the bifurcation sphere.
  float min_fork_angle_deg = 12.0f;
  float max_fork_angle_deg = 150.0f;
  // A junction may use at most this fraction of the distance to the next fork on a branch
  // (two neighbours together never meet), and this fraction of the way to a tip or the base.
  float fork_share = 0.45f;
  float end_share = 0.7f;
  // Angular gap (degrees) kept between the cross-sections of two branches seen from the fork.
  float junction_margin_deg = 3.0f;
  // Bark uv are metres divided by this (bark_tile_meters of the species' bark pattern), so
  // one texture tile covers this many metres in u and v on every branch.
  float bark_tile_meters = 1.0f;
};

// One ring of the tube mesh: vertices [first_vertex, first_vertex + sides] (the last one
// repeats the first position at the far side of the texture seam). Exposed for tests and tools.
struct TubeRing {
  uint32_t node = 0;          // graph node nearest the ring along its chain
  uint32_t chain = 0;         // chain index
  uint32_t piece = 0;         // tube piece index (a chain is cut into pieces at joined forks)
  double s = 0.0;             // spline parameter along the chain
  glm::vec3 center{0.0f};
  glm::vec3 tangent{0.0f, 1.0f, 0.0f};  // normal of the ring's plane, along the chain
  glm::vec3 normal{1.0f, 0.0f, 0.0f};   // frame: vertex k at angle 2πk/sides from normal
  float radius = 0.0f;
  uint32_t sides = 0;
  uint32_t first_vertex = 0;
};

struct BranchMeshInfo {
  std::vector<TubeRing> rings;          // in piece order, each piece's rings along its chain
  std::vector<uint32_t> cap_vertices;   // the apex vertex of each chain's tip cone
  std::vector<uint32_t> start_cap_vertices;  // the center of each embedded start's flat cap
  size_t chains = 0;
  size_t pieces = 0;
  size_t junctions = 0;                 // forks joined by a junction surface
  size_t junction_triangles = 0;
  size_t embedded_starts = 0;           // side branches closed at their start instead (fallback)
  uint32_t base_ring_sides = 0;         // sides of the open base ring (0: no open base)
};

// Number of ring sides for a chain of base radius r, the trunk's being r_max.
int ring_sides(float r, float r_max, const MesherParams& params);

// Decomposes the graph into chains (a chain follows its thickest child; other children start
// new chains at their parent's position) and sweeps rings along each chain's spline. Every
// ring point is at distance radius from the ring center in the plane normal to the tangent;
// a cone closes each tip. At a fork all branches (the incoming one, its continuation and the
// side branches) are cut where they leave the largest pairwise bifurcation sphere, and the cut
// rings are joined by the convex hull of their projections onto a sphere around the fork
// (see mesher_forks.cpp). Bark uv are physical, in tiles of params.bark_tile_meters, so the
// texture has the same texel density on every branch: u runs around the ring's polygon,
// u = (k / sides − 1/2) · perimeter / tile for vertex k (the seam, vertex 0 and its copy k =
// sides, at u = ∓perimeter / 2tile: a texture discontinuity where the perimeter is not a
// whole number of tiles); v = −(arc length along the axis) / tile, continued from the parent
// at forks. v decreases toward the tip so that, seen from outside, the texture stands upright
// with +u to the right: the tangent frame (+u, −v, outward normal) is right-handed. Junction
// surfaces and caps get vertices of their own whose uv unfold them at the same scale.
Mesh mesh_branches(const TreeGraph& graph, const MesherParams& params = {},
                   BranchMeshInfo* info = nullptr);

// The leaf card in local space: a quad covering the leaf texture, blade from the origin
// along +Y to y = 1, x in [−w/2, w/2] with w = shape's aspect, normal +Z, counter-clockwise
// seen from +Z; uv (0, 0) at the texture's top left = the blade's tip on the left.
Mesh make_leaf_card(LeafShape shape = LeafShape::ovate);

// The transform of a leaf card vertex into model space.
glm::vec3 leaf_to_model(const LeafPlacement& leaf, glm::vec3 local);

// A sphere (xyz center, w radius) containing every branch vertex and every vertex of every
// placed leaf card: Ritter's approximation, then grown to include all points exactly, with a
// tiny margin against float rounding.
glm::vec4 bounding_sphere(const Mesh& branches, const Mesh& leaf_card,
                          const std::vector<LeafPlacement>& leaves);

// Edges used by exactly one triangle after welding vertices of equal position (texture seams
// are not holes). A closed branch mesh has none but the base ring's.
size_t count_boundary_edges(const Mesh& mesh);

}  // namespace forest
