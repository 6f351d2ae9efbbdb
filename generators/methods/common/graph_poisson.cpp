#include "generators/methods/common/graph_poisson.h"
#include "generators/core/limits.h"

#include <algorithm>
#include <cmath>

#include "generators/core/input_error.h"

namespace forest {

namespace {
}

std::vector<glm::vec3> poisson_disc(const InsideFn& inside, Box box, size_t count, float spacing,
                                    Rng& rng, size_t max_tries) {
  std::vector<glm::vec3> points;
  if (count == 0 || !(spacing > 0.0f)) return points;
  glm::vec3 ext = glm::max(box.hi - box.lo, glm::vec3(1e-6f));
  // Cell edge = spacing: a conflicting point lies in the 27 cells around the dart.
  double cells_d = 1.0;
  int dims[3];
  for (int a = 0; a < 3; ++a) {
    dims[a] = std::max(1, int(std::ceil(double(ext[a]) / double(spacing))));
    cells_d *= double(dims[a]);
  }
  if (cells_d > double(kMaxPoissonCells))
    throw InputError("graph volume of " + std::to_string(ext.x) + " x " + std::to_string(ext.y) +
                     " x " + std::to_string(ext.z) + " m at node spacing " +
                     std::to_string(spacing) + " m needs too many grid cells");
  std::vector<int32_t> head(size_t(cells_d), -1);
  std::vector<int32_t> next;
  points.reserve(count);
  next.reserve(count);
  const float d2 = spacing * spacing;
  auto cell_of = [&](glm::vec3 p, int c[3]) {
    for (int a = 0; a < 3; ++a)
      c[a] = std::clamp(int((p[a] - box.lo[a]) / spacing), 0, dims[a] - 1);
  };
  for (size_t tries = 0; tries < max_tries && points.size() < count; ++tries) {
    glm::vec3 p(box.lo.x + float(rng.uniform()) * ext.x, box.lo.y + float(rng.uniform()) * ext.y,
                box.lo.z + float(rng.uniform()) * ext.z);
    if (!inside(p)) continue;
    int c[3];
    cell_of(p, c);
    bool ok = true;
    for (int z = std::max(0, c[2] - 1); ok && z <= std::min(dims[2] - 1, c[2] + 1); ++z)
      for (int y = std::max(0, c[1] - 1); ok && y <= std::min(dims[1] - 1, c[1] + 1); ++y)
        for (int x = std::max(0, c[0] - 1); ok && x <= std::min(dims[0] - 1, c[0] + 1); ++x)
          for (int32_t i = head[(size_t(z) * dims[1] + y) * dims[0] + x]; i >= 0; i = next[size_t(i)]) {
            glm::vec3 d = points[size_t(i)] - p;
            if (glm::dot(d, d) < d2) {
              ok = false;
              break;
            }
          }
    if (!ok) continue;
    size_t cell = (size_t(c[2]) * dims[1] + c[1]) * dims[0] + c[0];
    next.push_back(head[cell]);
    head[cell] = int32_t(points.size());
    points.push_back(p);
  }
  return points;
}

double estimate_volume(const InsideFn& inside, Box box, Rng& rng) {
  glm::vec3 ext = box.hi - box.lo;
  const int n = 16;  // 16^3 strata
  int hits = 0;
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        glm::vec3 u((float(x) + float(rng.uniform())) / n, (float(y) + float(rng.uniform())) / n,
                    (float(z) + float(rng.uniform())) / n);
        if (inside(box.lo + u * ext)) ++hits;
      }
  return double(ext.x) * ext.y * ext.z * double(hits) / double(n * n * n);
}

float spacing_for_count(double volume, size_t count, double fill) {
  if (count == 0 || volume <= 0.0) return 0.0f;
  return float(std::cbrt(6.0 * fill * volume / (3.14159265358979323846 * double(count))));
}

}  // namespace forest
