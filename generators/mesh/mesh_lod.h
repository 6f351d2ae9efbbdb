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
// welded by position (one vertex per position, so texture seams and junction copies lock
// nothing), so a closed LOD0 gives closed levels. Open borders (the trunk's base ring) are
// locked so the tree keeps its footing. Each corner of a simplified triangle then takes the
// LOD0 vertex at its position whose uv agree best with the other corners', so the texture
// seams stay where LOD0 has them; a triangle left across a seam (its seam vertex collapsed
// away) gets a new vertex that continues one side's uv. Each level's error is meshopt's
// relative error times meshopt_simplifyScale, i.e. meters, taken as the running maximum so
// that errors never decrease along the chain. A level that does not remove at least 10% of
// the previous level's triangles ends the chain. Every level is optimized (optimize_mesh)
// and holds only the vertices it uses.
std::vector<MeshLod> simplify_lods(const Mesh& lod0, std::span<const float> fractions,
                                   float max_relative_error = 0.25f);

// `source` simplified by edge collapses (meshopt_simplify on the surface welded by position,
// open borders locked, corners then taking the source variant whose uv fit, as above) toward
// `target_triangles`, moving the surface by at most `max_error` metres; error = meshopt's,
// in metres against `source`. Optimized; back-to-back duplicates are left to the caller.
MeshLod simplify_to(const Mesh& source, size_t target_triangles, float max_error);

// How far (metres) simplify_to would move `mesh` to reach each of `targets` triangles, at most
// `max_error`: the collapses alone, without building the levels.
std::vector<float> collapse_errors(const Mesh& mesh, std::span<const size_t> targets, float max_error);

// The coarsest level: `source` welded by position and simplified by meshopt_simplifySloppy
// (vertex clustering: it merges whatever lies close, so it reaches counts that edge collapses
// on thin tubes cannot) to about `target_triangles`, with the uv repair of simplify_lods and
// without back-to-back duplicates. Its error is meshopt's relative error times
// meshopt_simplifyScale (metres, against `source`). An empty mesh when nothing is left.
MeshLod sloppy_lod(const Mesh& source, size_t target_triangles);

// Triangles whose three corner positions another triangle has too, with the other winding:
// two faces back to back enclosing nothing (a tube flattened into a fin). Counted, and removed
// in pairs (a duplicate of the same winding is removed too, one copy stays).
size_t count_back_to_back(const Mesh& mesh);
size_t remove_back_to_back(Mesh& mesh);

}  // namespace forest
