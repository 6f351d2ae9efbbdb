// Skeleton from the visual hull (Shlyakhter 2001 step 3).
// 1. Tips per view: the interesting points of each mask's outline, from the hierarchy of its
//    convex hulls (outline_tips.h), lifted to 3D on the hull along their pixel rays.
// 2. Approximate medial axis: the hull's voxels are thinned in order of their distance to the
//    hull boundary, keeping the topology and the marked voxels (the one nearest to each tip and
//    to the trunk base) -- distance-ordered homotopic thinning (voxel_thinning.h). What is
//    left are thin curves along the medial axis joining the marked voxels.
// 3. Graph: the remaining voxels with 26-adjacency, thinned to a tree -- a breadth-first tree
//    from the base, then unmarked end nodes removed until every end is marked.
// 4. Second pass, one more branching level: the hull voxels farthest from that skeleton (each
//    farther than max(4 cells, half the largest boundary distance), greedily, at most
//    `extra_branches`) are marked too and the hull is thinned again with all marks.
// 5. Voxel chains are simplified where the shortcut stays inside the hull (exact segment test).
#pragma once
#include <vector>

#include "generators/methods/visual_hull/outline_tips.h"
#include "generators/methods/visual_hull/visual_hull_hull.h"
#include "generators/tree/tree_graph.h"

namespace forest {

struct SkeletonParams {
  int voxels = 48;           // voxel cells along the longest side of the bounds
  int tips_per_view = 6;     // interesting points kept per view
  int extra_branches = 8;    // second-pass marks (one more branching level)
  OutlineTipParams tips;
};

struct HullSkeleton {
  TreeGraph graph;                // node 0 = trunk base; parent < own index; radii 0
  std::vector<uint32_t> marked;   // nodes that were tips, second-pass ends or the base
  size_t lifted_tips = 0;         // tips found on the hull (before merging duplicates)
  size_t marks = 0;               // distinct marked voxels (all of them are kept as nodes)
  size_t second_pass = 0;         // marks added by the second pass
};

HullSkeleton hull_skeleton(const ViewSet& set, const VoxelGrid& grid, const SkeletonParams& params);

}  // namespace forest
