#include "generators/tree/crown_depth.h"

#include <algorithm>
#include <cmath>

#include "generators/tree/convex_hull.h"
#include "generators/tree/habit.h"

namespace forest {

std::vector<double> depths_below_hull(std::span<const glm::vec3> points) {
  ConvexHull hull = convex_hull(points);
  std::vector<double> depth(points.size(), 0.0);
  for (size_t i = 0; i < points.size(); ++i) depth[i] = depth_below_hull(hull, glm::dvec3(points[i]));
  return depth;
}

double quantile(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return 0.0;
  double pos = std::clamp(q, 0.0, 1.0) * double(sorted.size() - 1);
  size_t i = std::min(size_t(pos), sorted.size() - 1);
  size_t j = std::min(i + 1, sorted.size() - 1);
  return sorted[i] + (sorted[j] - sorted[i]) * (pos - double(i));
}

CrownDepth measure_crown_depth(std::span<const LeafPlacement> leaves) {
  CrownDepth c;
  c.leaves = uint32_t(leaves.size());
  if (leaves.empty()) return c;
  std::vector<glm::vec3> points;
  points.reserve(leaves.size());
  for (const LeafPlacement& l : leaves) points.push_back(l.position);
  glm::vec2 extent = horizontal_extent(points);
  c.half_width = 0.25f * (extent.x + extent.y);
  ConvexHull hull = convex_hull(points);
  c.solid = hull.solid();
  std::vector<double> depth(points.size());
  for (size_t i = 0; i < points.size(); ++i) depth[i] = depth_below_hull(hull, glm::dvec3(points[i]));
  std::sort(depth.begin(), depth.end());
  c.q1 = float(quantile(depth, 0.25));
  c.median = float(quantile(depth, 0.5));
  c.q3 = float(quantile(depth, 0.75));
  const double unit = c.half_width > 0.0f ? double(c.half_width) : 0.0;
  if (unit > 0.0) {
    c.q1_rel = float(c.q1 / unit), c.median_rel = float(c.median / unit), c.q3_rel = float(c.q3 / unit);
    for (double d : depth) {
      size_t bin = std::min(size_t(std::floor(d / unit * double(kCrownDepthBins))), kCrownDepthBins - 1);
      c.histogram[bin] += 1.0f;
    }
  } else {
    c.histogram[0] = float(depth.size());  // no width: every leaf in the first bin
  }
  for (float& h : c.histogram) h /= float(depth.size());
  return c;
}

}  // namespace forest
