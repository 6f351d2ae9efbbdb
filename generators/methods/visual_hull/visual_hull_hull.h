// The visual hull of a view set (Shlyakhter 2001 step 2): the intersection of the silhouette cones
// of all masks, clipped to the view set's bounds. Represented implicitly and exactly for the
// pixelated masks: a pixel is a square, its cone a polyhedron, and along any ray every
// view's membership is piecewise constant between the ray's crossings of that view's pixel
// grid lines -- crossings solved in closed form (clip coordinates are linear in the ray
// parameter). This is the image-based visual hull idea (Matusik et al. 2000) and plays the
// role of the paper's polyhedral hull: point tests, segment tests and reprojection are exact,
// so "no segment outside the hull" and "reprojection IoU" are measured, not approximated.
#pragma once
#include <vector>

#include "generators/methods/common/image_inputs.h"

namespace forest {

struct Interval {
  double a = 0.0;
  double b = 0.0;
};

// Whether world point p is inside the hull: in bounds, and in front of every camera and on
// a silhouette pixel (alpha >= 0.5) in every view.
bool inside_hull(const ViewSet& set, glm::dvec3 p);

// Sorted disjoint intervals of t in [t0, t1] where origin + t * dir is inside the hull.
// `skip_view` leaves one view out (reprojection into that view).
std::vector<Interval> hull_intervals(const ViewSet& set, glm::dvec3 origin, glm::dvec3 dir,
                                     double t0, double t1, int skip_view = -1);

// The largest s in [0, 1] such that p + t (q - p) is in the hull for all t in [0, s];
// 0 when p itself is outside. 1 means the whole segment is inside.
double inside_fraction(const ViewSet& set, glm::dvec3 p, glm::dvec3 q);
bool segment_inside_hull(const ViewSet& set, glm::dvec3 p, glm::dvec3 q);

// Hull volume by exact vertical ray integration over a columns x columns grid of the bounds.
double hull_volume(const ViewSet& set, int columns);

// Reprojection of the hull into view `v` at the mask resolution (a pixel is covered when the
// ray through its centre meets the hull) and its intersection-over-union with the mask.
double reprojection_iou(const ViewSet& set, size_t v);

// Voxel occupancy of the hull: n cells along the longest side of the bounds (cubic cells);
// a cell is occupied when its centre is inside the hull.
struct VoxelGrid {
  glm::ivec3 dims{0};
  glm::dvec3 origin{0.0};  // corner of cell (0, 0, 0)
  double cell = 1.0;
  std::vector<uint8_t> occupied;
  size_t index(int x, int y, int z) const { return (size_t(z) * size_t(dims.y) + size_t(y)) * size_t(dims.x) + size_t(x); }
  glm::dvec3 center(int x, int y, int z) const { return origin + (glm::dvec3(x, y, z) + 0.5) * cell; }
};
VoxelGrid voxelize_hull(const ViewSet& set, int n);

}  // namespace forest
