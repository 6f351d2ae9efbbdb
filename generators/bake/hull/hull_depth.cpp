#include "generators/bake/hull/hull_depth.h"

#include <algorithm>
#include <cmath>
#include <thread>

#include <Eigen/Dense>

#include "generators/core/input_error.h"

namespace forest {

namespace {

// b_k(ω) = max(±ω_i, 0)², k = 2i (+) or 2i + 1 (−).
std::array<double, 6> basis(glm::vec3 w) {
  std::array<double, 6> b{};
  for (int i = 0; i < 3; ++i) {
    double c = double(w[i]);
    b[size_t(2 * i)] = c > 0.0 ? c * c : 0.0;
    b[size_t(2 * i + 1)] = c < 0.0 ? c * c : 0.0;
  }
  return b;
}

// (BᵀB)⁻¹ Bᵀ for the fixed directions: row k, column j = weight of depth sample j in D_k.
// The same for every leaf, so computed once.
struct Fit {
  std::array<glm::vec3, kCrownDirections> dirs;
  float weight[6][kCrownDirections];
};

const Fit& fit() {
  static const Fit f = [] {
    Fit r;
    Eigen::Matrix<double, kCrownDirections, 6> B;
    for (int j = 0; j < kCrownDirections; ++j) {
      r.dirs[size_t(j)] = crown_direction(j);
      std::array<double, 6> b = basis(r.dirs[size_t(j)]);
      for (int k = 0; k < 6; ++k) B(j, k) = b[size_t(k)];
    }
    Eigen::Matrix<double, 6, 6> normal = B.transpose() * B;
    Eigen::Matrix<double, 6, kCrownDirections> pinv = normal.inverse() * B.transpose();
    for (int k = 0; k < 6; ++k)
      for (int j = 0; j < kCrownDirections; ++j) r.weight[k][j] = float(pinv(k, j));
    return r;
  }();
  return f;
}

// Trilinear F on the grid; 0 outside it.
float sample(const ScalarGrid& g, glm::vec3 q) {
  glm::vec3 u = (q - g.origin) / g.spacing;
  glm::vec3 f = glm::floor(u);
  glm::ivec3 i(f);
  if (i.x < 0 || i.y < 0 || i.z < 0 || i.x + 1 >= g.size.x || i.y + 1 >= g.size.y || i.z + 1 >= g.size.z)
    return 0.0f;
  glm::vec3 t = u - f;
  const size_t sx = 1, sy = size_t(g.size.x), sz = size_t(g.size.x) * size_t(g.size.y);
  const float* v = &g.values[g.index(i.x, i.y, i.z)];
  float c00 = v[0] + t.x * (v[sx] - v[0]);
  float c10 = v[sy] + t.x * (v[sy + sx] - v[sy]);
  float c01 = v[sz] + t.x * (v[sz + sx] - v[sz]);
  float c11 = v[sz + sy] + t.x * (v[sz + sy + sx] - v[sz + sy]);
  float c0 = c00 + t.y * (c10 - c00);
  float c1 = c01 + t.y * (c11 - c01);
  return c0 + t.z * (c1 - c0);
}

// Length of p + t ω (t ≥ 0) with F ≥ iso, midpoint rule with step h, until the grid's box.
float depth_along(const ScalarGrid& g, float iso, glm::vec3 p, glm::vec3 w, float h, float t_max) {
  float inside = 0.0f;
  for (float t = 0.5f * h; t < t_max; t += h)
    if (sample(g, p + t * w) >= iso) inside += h;
  return inside;
}

// Ray parameter where p + t ω leaves the box [lo, hi] (p inside or not; 0 if it never enters).
float exit_distance(glm::vec3 p, glm::vec3 w, glm::vec3 lo, glm::vec3 hi) {
  float t = 1e30f;
  for (int i = 0; i < 3; ++i) {
    if (w[i] > 1e-9f) t = std::min(t, (hi[i] - p[i]) / w[i]);
    else if (w[i] < -1e-9f) t = std::min(t, (lo[i] - p[i]) / w[i]);
  }
  return std::max(t, 0.0f);
}

}  // namespace

glm::vec3 crown_direction(int j) {
  // Fibonacci sphere: z uniform in (−1, 1), golden-angle azimuth.
  const double golden = 3.14159265358979323846 * (3.0 - std::sqrt(5.0));
  double y = 1.0 - (2.0 * j + 1.0) / kCrownDirections;
  double s = std::sqrt(std::max(0.0, 1.0 - y * y));
  double a = golden * j;
  return glm::normalize(glm::vec3(float(s * std::cos(a)), float(y), float(s * std::sin(a))));
}

std::vector<CrownCube> crown_depths(const MetaballField& field, float iso, std::span<const glm::vec3> points,
                                     const CrownDepthParams& params) {
  std::vector<CrownCube> out(points.size(), CrownCube{});
  if (field.centers.empty() || points.empty()) return out;
  if (!(params.step_fraction > 0.0f) || !(iso > 0.0f) || params.max_cells_per_axis < 8)
    throw InputError("", 0, "crown_depths", "step and iso must be positive, max_cells_per_axis >= 8");
  glm::vec3 lo(field.centers[0]), hi(field.centers[0]);
  for (const glm::vec3& p : field.centers) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const float span = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}) + 2.0f * field.radius;
  const float h = std::max(field.radius * params.step_fraction, span / float(params.max_cells_per_axis - 4));
  const ScalarGrid grid = sample_field(field, h);
  const glm::vec3 box_lo = grid.origin;
  const glm::vec3 box_hi = grid.origin + grid.spacing * glm::vec3(grid.size - 1);
  const Fit& f = fit();

  auto run = [&](size_t begin, size_t end) {
    float d[kCrownDirections];
    for (size_t i = begin; i < end; ++i) {
      const glm::vec3 p = points[i];
      for (int j = 0; j < kCrownDirections; ++j) {
        glm::vec3 w = f.dirs[size_t(j)];
        d[j] = depth_along(grid, iso, p, w, h, exit_distance(p, w, box_lo, box_hi));
      }
      for (int k = 0; k < 6; ++k) {
        float s = 0.0f;
        for (int j = 0; j < kCrownDirections; ++j) s += f.weight[k][j] * d[j];
        out[i][size_t(k)] = std::max(s, 0.0f);
      }
    }
  };
  // Leaves are independent: contiguous chunks per thread give the same bits at any count.
  const size_t n = points.size();
  const unsigned threads = std::clamp(std::thread::hardware_concurrency(), 1u, 16u);
  if (threads == 1 || n < 256) {
    run(0, n);
  } else {
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t)
      pool.emplace_back(run, n * t / threads, n * (t + 1) / threads);
    for (std::thread& t : pool) t.join();
  }
  return out;
}

double mesh_volume(const Mesh& mesh) {
  double v = 0.0;
  for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    glm::dvec3 a(mesh.vertices[mesh.indices[i]].position), b(mesh.vertices[mesh.indices[i + 1]].position),
        c(mesh.vertices[mesh.indices[i + 2]].position);
    v += glm::dot(a, glm::cross(b, c));
  }
  return v / 6.0;
}

float crown_extinction(const TreeModel& model, const Mesh& hull) {
  const double volume = mesh_volume(hull);
  if (!(volume > 0.0) || model.leaves.empty()) return 0.0f;
  double card = 0.0;
  const Mesh& c = model.leaf_card;
  for (size_t i = 0; i + 2 < c.indices.size(); i += 3) {
    glm::dvec3 a(c.vertices[c.indices[i]].position), b(c.vertices[c.indices[i + 1]].position),
        d(c.vertices[c.indices[i + 2]].position);
    card += 0.5 * glm::length(glm::cross(b - a, d - a));
  }
  double coverage = 1.0;  // the fraction of the card the alpha test keeps
  const Image8& t = model.leaf_texture;
  if (!t.rgba.empty()) {
    size_t kept = 0;
    for (size_t i = 3; i < t.rgba.size(); i += 4) kept += t.rgba[i] >= 128;
    coverage = double(kept) / double(t.rgba.size() / 4);
  }
  double area = 0.0;
  for (const LeafPlacement& l : model.leaves) area += double(l.scale) * double(l.scale);
  area *= card * coverage;
  double kappa = 0.5 * area / volume;
  return float(std::clamp(kappa, double(kMinCrownExtinction), double(kMaxCrownExtinction)));
}

void attach_crown_light(TreeModel& model, const Hull& hull, const CrownDepthParams& params) {
  if (hull.mesh.indices.empty() || model.leaves.empty()) return;
  std::vector<glm::vec3> centers;
  centers.reserve(model.leaves.size());
  for (const LeafPlacement& l : model.leaves) centers.push_back(leaf_center(l));
  MetaballField field = make_metaball_field(centers, hull.radius);
  CrownLight c;
  c.extinction = crown_extinction(model, hull.mesh);
  if (!(c.extinction > 0.0f)) return;  // no enclosed volume: nothing to shadow with
  c.depths = crown_depths(field, hull.iso, centers, params);
  model.bake.crown = std::move(c);
}

}  // namespace forest
