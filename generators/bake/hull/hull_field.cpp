#include "generators/bake/hull/hull_field.h"
#include "generators/core/limits.h"

#include <algorithm>
#include <cmath>

#include "generators/core/input_error.h"

namespace forest {

namespace {

// Bucket grids beyond this many cells get coarser cells (still >= radius): a stray far-away
// leaf must not exhaust memory.
// Sample grids beyond this many points are refused (the caller caps its resolution first).

bool finite(glm::vec3 p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

glm::ivec3 bucket_of(const MetaballField& f, glm::vec3 q) {
  glm::vec3 c = glm::floor((q - f.origin) / f.cell);
  // Clamp in float first: a far query must not overflow the int conversion.
  c = glm::clamp(c, glm::vec3(-1.0f), glm::vec3(f.cells));
  return glm::ivec3(c);
}

// Calls visit(i) for every generator in the 27 buckets around q (a superset of those whose
// ball contains q), in a fixed order.
template <class Visit>
void for_near(const MetaballField& f, glm::vec3 q, Visit&& visit) {
  if (f.centers.empty()) return;
  glm::ivec3 b = bucket_of(f, q);
  glm::ivec3 lo = glm::max(b - 1, glm::ivec3(0)), hi = glm::min(b + 1, f.cells - 1);
  for (int z = lo.z; z <= hi.z; ++z)
    for (int y = lo.y; y <= hi.y; ++y)
      for (int x = lo.x; x <= hi.x; ++x) {
        size_t c = (size_t(z) * size_t(f.cells.y) + size_t(y)) * size_t(f.cells.x) + size_t(x);
        for (uint32_t k = f.cell_start[c]; k < f.cell_start[c + 1]; ++k) visit(f.order[k]);
      }
}

}  // namespace

MetaballField make_metaball_field(std::vector<glm::vec3> centers, float radius) {
  if (!(radius > 0.0f) || !std::isfinite(radius))
    throw InputError("", 0, "radius", "metaball radius must be positive and finite");
  for (size_t i = 0; i < centers.size(); ++i)
    if (!finite(centers[i]))
      throw InputError("", 0, "leaves", "leaf " + std::to_string(i) + " has a non-finite position");
  MetaballField f;
  f.radius = radius;
  f.centers = std::move(centers);
  if (f.centers.empty()) return f;

  glm::vec3 lo(f.centers[0]), hi(f.centers[0]);
  for (const glm::vec3& p : f.centers) lo = glm::min(lo, p), hi = glm::max(hi, p);
  glm::dvec3 extent = glm::dvec3(hi - lo);
  double cell = radius;
  for (int guard = 0; guard < 64; ++guard) {
    glm::dvec3 n = glm::floor(extent / cell) + 1.0;
    if (n.x * n.y * n.z <= kMaxHullBucketCells) break;
    cell *= 1.5;
  }
  f.cell = float(cell);
  f.origin = lo;
  f.cells = glm::ivec3(glm::floor(extent / cell)) + 1;

  // Counting sort of the generators into buckets: order within a bucket = index order.
  size_t ncells = size_t(f.cells.x) * size_t(f.cells.y) * size_t(f.cells.z);
  std::vector<uint32_t> bucket(f.centers.size());
  f.cell_start.assign(ncells + 1, 0);
  for (size_t i = 0; i < f.centers.size(); ++i) {
    glm::ivec3 b = glm::clamp(bucket_of(f, f.centers[i]), glm::ivec3(0), f.cells - 1);
    bucket[i] = uint32_t((size_t(b.z) * size_t(f.cells.y) + size_t(b.y)) * size_t(f.cells.x) + size_t(b.x));
    ++f.cell_start[bucket[i] + 1];
  }
  for (size_t c = 0; c < ncells; ++c) f.cell_start[c + 1] += f.cell_start[c];
  f.order.resize(f.centers.size());
  std::vector<uint32_t> fill(f.cell_start.begin(), f.cell_start.end() - 1);
  for (size_t i = 0; i < f.centers.size(); ++i) f.order[fill[bucket[i]]++] = uint32_t(i);
  return f;
}

float field_value(const MetaballField& f, glm::vec3 q) {
  const float r2 = f.radius * f.radius;
  float sum = 0.0f;
  for_near(f, q, [&](uint32_t i) {
    glm::vec3 d = q - f.centers[i];
    sum += metaball_kernel(glm::dot(d, d), r2);
  });
  return sum;
}

glm::vec3 field_gradient(const MetaballField& f, glm::vec3 q) {
  // dD/dq = 2 t * (-2 (q - p) / r^2), t = 1 - |q - p|^2 / r^2.
  const float r2 = f.radius * f.radius;
  glm::vec3 g(0.0f);
  for_near(f, q, [&](uint32_t i) {
    glm::vec3 d = q - f.centers[i];
    float d2 = glm::dot(d, d);
    if (d2 < r2) g += (-4.0f * (1.0f - d2 / r2) / r2) * d;
  });
  return g;
}

std::vector<float> field_at_centers(const MetaballField& f) {
  std::vector<float> out(f.centers.size());
  for (size_t i = 0; i < f.centers.size(); ++i) out[i] = field_value(f, f.centers[i]);
  return out;
}

ScalarGrid sample_field(const MetaballField& f, float spacing) {
  if (!(spacing > 0.0f) || !std::isfinite(spacing))
    throw InputError("", 0, "spacing", "grid spacing must be positive and finite");
  ScalarGrid g;
  g.spacing = spacing;
  if (f.centers.empty()) return g;
  glm::vec3 lo(f.centers[0]), hi(f.centers[0]);
  for (const glm::vec3& p : f.centers) lo = glm::min(lo, p), hi = glm::max(hi, p);
  // One spacing of margin beyond every ball: the border samples are 0, the surface closed.
  const float margin = f.radius + spacing;
  g.origin = lo - margin;
  glm::dvec3 n = glm::ceil(glm::dvec3(hi - lo + 2.0f * margin) / double(spacing)) + 1.0;
  if (n.x * n.y * n.z > kMaxHullGridPoints)
    throw InputError("", 0, "spacing", "metaball grid too fine for the crown's extent");
  g.size = glm::ivec3(n);
  g.values.assign(size_t(g.size.x) * size_t(g.size.y) * size_t(g.size.z), 0.0f);

  const float r2 = f.radius * f.radius;
  for (const glm::vec3& p : f.centers) {
    glm::ivec3 a = glm::ivec3(glm::ceil((p - f.radius - g.origin) / spacing));
    glm::ivec3 b = glm::ivec3(glm::floor((p + f.radius - g.origin) / spacing));
    a = glm::max(a, glm::ivec3(0));
    b = glm::min(b, g.size - 1);
    for (int k = a.z; k <= b.z; ++k)
      for (int j = a.y; j <= b.y; ++j)
        for (int i = a.x; i <= b.x; ++i) {
          glm::vec3 d = g.point(i, j, k) - p;
          g.values[g.index(i, j, k)] += metaball_kernel(glm::dot(d, d), r2);
        }
  }
  return g;
}

}  // namespace forest
