// Skeleton from the visual hull (seed 003 step 3).
// 1. "Interesting points" per view: vertices of the convex hull of the silhouette, ranked by
//    the sharpness of the hull corner and by the pockets of the edges next to it (pocket
//    depth = how far the outline falls back from the hull edge; long edges count too). The
//    best ones are branch tips seen in that view.
// 2. Tips are lifted to 3D on the hull along their pixel rays.
// 3. Medial axis: [ours] instead of the paper's Voronoi-node thinning we thin the hull's voxel
//    graph to the penalized shortest-path tree of TEASAR (Sato et al. 2000): Dijkstra from the
//    trunk base with a step cost that explodes near the hull boundary, so paths run along the
//    medial axis; the union of the paths from the marked nodes (tips, base) to the base is the
//    skeleton -- a tree by construction, keeping every marked node. A second pass adds one
//    more branching level: the hull voxel farthest from the current skeleton (outside a
//    tube of radius ~ its distance to the boundary) adds its path, repeatedly.
// 4. Chains are simplified where the shortcut stays inside the hull (exact segment test).
#pragma once
#include <vector>

#include "generators/methods/visual_hull_hull.h"
#include "generators/tree/tree_graph.h"

namespace forest {

struct SkeletonParams {
  int voxels = 48;           // voxel cells along the longest side of the bounds
  int tips_per_view = 6;     // interesting points kept per view
  int extra_branches = 8;    // second-pass paths (one more branching level)
  double min_tip_separation = 0.08;  // of the mask diagonal, between tips of one view
};

// Interesting points of one mask (pixel centres), best first, at most `count`.
std::vector<glm::dvec2> interesting_points(const Mask& mask, int count, double min_separation);

struct HullSkeleton {
  TreeGraph graph;                // node 0 = trunk base; parent < own index; radii 0
  std::vector<uint32_t> marked;   // nodes that were tips or the base (kept by thinning)
  size_t lifted_tips = 0;         // tips found on the hull (before merging duplicates)
};

HullSkeleton hull_skeleton(const ViewSet& set, const VoxelGrid& grid, const SkeletonParams& params);

}  // namespace forest
