// Structural branch LOD (after SpeedTree's and Nanite foliage's twig removal): coarser bark
// levels built from the tree graph itself, not only by collapsing edges of LOD0. A level
// aiming at a triangle count first asks how far edge collapses alone would have to move the
// surface to get there (meshopt_simplify of the level before); within that distance it then
// drops whole chains (twigs, then branches) narrower than it, together with everything that
// grows on them, and sweeps the rest with as few ring sides as stay within it; the mesher
// rebuilds a closed, joined surface from that graph (a removed side branch leaves no hole:
// its fork is no fork any more), and edge collapses within the same distance finish the
// level. Thin tubes thus go whole instead of collapsing into back-to-back fins, and the chain
// reaches counts collapses alone cannot. The leaves are not bark: they stay. The chain ends
// with a sloppy-simplified level (meshopt_simplifySloppy, mesh_lod.h) for the farthest trees.
//
// Errors are metres in model space, as the cull pass's projected-error choice expects
// (shaders/cull.comp): a removed chain of base radius r is a silhouette 2r wide that
// disappears; a ring of radius r swept with n sides stands up to r (1 − cos π/n) inside the
// circle; the collapses add meshoptimizer's error. A level's error is the sum of its
// structural and its collapse error, and errors never decrease along the chain.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "generators/mesh/mesher.h"
#include "generators/model/tree_model.h"
#include "generators/tree/tree_graph.h"

namespace forest {

struct StructuralLodParams {
  // Triangles each structural level aims at, as fractions of LOD0's. A level that does not
  // remove at least 10 % of the previous level's triangles is skipped.
  std::vector<float> fractions = {0.5f, 0.25f, 0.12f, 0.06f, 0.03f};
  // The coarsest level (sloppy) aims at this fraction of LOD0's triangles.
  float sloppy_fraction = 0.012f;
};

// One chain of the graph as the LOD planner sees it (exposed for tests).
struct LodChain {
  float base_radius = 0.0f;   // radius where the chain starts (its own, not its parent's)
  int32_t parent = -1;        // the chain it branches off (-1: a root chain)
  uint32_t rings = 0;         // rings LOD0 swept along it
  uint32_t sides = 0;         // LOD0's ring sides
};

// Chains of `graph` in mesh_branches' order with their LOD0 ring counts (from `info`).
std::vector<LodChain> lod_chains(const TreeGraph& graph, const BranchMeshInfo& info);

// `graph` without the chains not in `keep` (index-aligned with lod_chains) and everything
// that grows on them; leaves are not copied. Node order (so parent < own index) is kept.
TreeGraph prune_chains(const TreeGraph& graph, const std::vector<char>& keep);

// The LOD chain below `lod0` = mesh_branches(graph, mesher, &info0): structural levels, then
// the sloppy level. Every level is optimized (optimize_mesh) and has no back-to-back
// duplicate triangles.
std::vector<MeshLod> structural_lods(const TreeGraph& graph, const MesherParams& mesher, const Mesh& lod0,
                                     const BranchMeshInfo& info0, const StructuralLodParams& params = {});

}  // namespace forest
