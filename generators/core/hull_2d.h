// The 2D convex hull of a point set: Andrew's monotone chain, counter-clockwise, without
// repeated end point; collinear points on an edge are dropped. Works on any point type with
// x and y (glm::dvec2; glm::i64vec2 for exact integer decisions). Fewer than 3 distinct
// points come back as they are (sorted, distinct).
#pragma once
#include <algorithm>
#include <vector>

namespace forest {

template <class Point>
std::vector<Point> convex_hull_2d(std::vector<Point> p) {
  std::sort(p.begin(), p.end(), [](Point a, Point b) { return a.x != b.x ? a.x < b.x : a.y < b.y; });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  auto cross = [](Point o, Point a, Point b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); };
  std::vector<Point> h(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {  // lower chain
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, t = k + 1; i-- > 0;) {  // upper chain
    while (k >= t && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

}  // namespace forest
