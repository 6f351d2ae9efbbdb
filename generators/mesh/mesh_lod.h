// Branch mesh post-processing with meshoptimizer: GPU-friendly ordering and a chain of
// simplified levels of detail with their geometric errors in model-space meters.
#pragma once
#include <span>
#include <vector>

#include "generators/model/tree_model.h"

namespace forest {

// Reorders triangles for the post-transform vertex cache, then vertices for fetch locality
// (dropping unreferenced ones). Same surface, same triangles.
void optimize_mesh(Mesh& mesh);

// Simplified versions of `lod0` (itself unchanged), each aiming at a fraction of its
// triangles (e.g. 0.5, 0.25, 0.12) by edge collapses (meshopt_simplify) on the surface
// welded by position, so a closed LOD0 gives closed levels. Open borders (the trunk's base
// ring) are locked so the tree keeps its footing. Each level's error is
// meshopt's relative error times meshopt_simplifyScale, i.e. meters, taken as the running
// maximum so that errors never decrease along the chain. A level that does not remove at
// least 10% of the previous level's triangles ends the chain. Every level is optimized
// (optimize_mesh) and holds only the vertices it uses.
std::vector<MeshLod> simplify_lods(const Mesh& lod0, std::span<const float> fractions,
                                   float max_relative_error = 0.25f);

}  // namespace forest
