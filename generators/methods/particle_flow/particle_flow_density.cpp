#include "generators/methods/particle_flow/particle_flow_density.h"

#include <algorithm>
#include <cmath>

#include <Eigen/IterativeLinearSolvers>

namespace forest {

namespace {

// Summed-area table of a mask: mean alpha over any pixel rectangle in O(1).
struct AlphaSums {
  int w = 0, h = 0;
  std::vector<double> s;  // (w + 1) x (h + 1)
  explicit AlphaSums(const Mask& m) : w(m.width), h(m.height), s(size_t(w + 1) * size_t(h + 1), 0.0) {
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i)
        s[size_t(j + 1) * size_t(w + 1) + size_t(i + 1)] = m.at(i, j) + s[size_t(j) * size_t(w + 1) + size_t(i + 1)] +
                                                          s[size_t(j + 1) * size_t(w + 1) + size_t(i)] -
                                                          s[size_t(j) * size_t(w + 1) + size_t(i)];
  }
  double sum(int i0, int j0, int i1, int j1) const {  // [i0, i1) x [j0, j1)
    auto at = [&](int i, int j) { return s[size_t(j) * size_t(w + 1) + size_t(i)]; };
    return at(i1, j1) - at(i0, j1) - at(i1, j0) + at(i0, j0);
  }
};

}  // namespace

DensityGrid make_density_grid(const Bounds& bounds, int n) {
  DensityGrid g;
  glm::dvec3 size = bounds.size();
  g.cell = std::max({size.x, size.y, size.z}) / n;
  g.dims = glm::max(glm::ivec3(glm::ceil(size / g.cell - 1e-9)), glm::ivec3(1));
  g.origin = bounds.min;
  g.alpha.assign(g.size(), 0.0);
  return g;
}

std::vector<double> initial_density(const DensityGrid& g, const ViewSet& views) {
  std::vector<double> out(g.size(), 1.0);
  for (const View& v : views.views) {
    AlphaSums sums(v.mask);
    for (size_t idx = 0; idx < g.size(); ++idx) {
      glm::ivec3 c = g.cell_of_index(idx);
      glm::dvec2 lo(1e300), hi(-1e300);
      bool in_front = true;
      for (int k = 0; k < 8; ++k) {
        Projection p = project(v.camera, g.corner(c + glm::ivec3(k & 1, (k >> 1) & 1, (k >> 2) & 1)));
        in_front = in_front && p.in_front();
        lo = glm::min(lo, p.pixel);
        hi = glm::max(hi, p.pixel);
      }
      double mean = 0.0;
      if (in_front) {
        int i0 = std::clamp(int(std::floor(lo.x)), 0, v.mask.width), i1 = std::clamp(int(std::ceil(hi.x)), 0, v.mask.width);
        int j0 = std::clamp(int(std::floor(lo.y)), 0, v.mask.height), j1 = std::clamp(int(std::ceil(hi.y)), 0, v.mask.height);
        if (i1 > i0 && j1 > j0) mean = sums.sum(i0, j0, i1, j1) / double((i1 - i0) * (j1 - j0));
      }
      out[idx] = std::min(out[idx], mean);
    }
  }
  return out;
}

Eigen::SparseMatrix<double, Eigen::RowMajor> projection_matrix(const DensityGrid& g, const ViewSet& views,
                                                               const std::vector<size_t>& columns) {
  std::vector<int64_t> column_of(g.size(), -1);
  for (size_t k = 0; k < columns.size(); ++k) column_of[columns[k]] = int64_t(k);
  size_t rows = 0;
  for (const View& v : views.views) rows += size_t(v.mask.width) * size_t(v.mask.height);
  std::vector<Eigen::Triplet<double>> entries;
  const glm::dvec3 lo = g.origin, hi = g.origin + glm::dvec3(g.dims) * g.cell;
  size_t row = 0;
  for (const View& v : views.views)
    for (int j = 0; j < v.mask.height; ++j)
      for (int i = 0; i < v.mask.width; ++i, ++row) {
        Ray r = pixel_ray(v.camera, {i + 0.5, j + 0.5});
        // Clip to the grid box, then walk the cells (Amanatides & Woo).
        double t0 = 0.0, t1 = 1e7;
        bool hit = true;
        for (int k = 0; k < 3 && hit; ++k) {
          if (std::abs(r.direction[k]) < 1e-300) {
            hit = r.origin[k] >= lo[k] && r.origin[k] <= hi[k];
            continue;
          }
          double ta = (lo[k] - r.origin[k]) / r.direction[k], tb = (hi[k] - r.origin[k]) / r.direction[k];
          if (ta > tb) std::swap(ta, tb);
          t0 = std::max(t0, ta);
          t1 = std::min(t1, tb);
          hit = t1 > t0;
        }
        if (!hit) continue;
        glm::dvec3 p = r.origin + r.direction * (0.5 * (t0 + std::min(t0 + 1e-9 * g.cell, t1)));
        glm::ivec3 c = glm::clamp(glm::ivec3(glm::floor((p - lo) / g.cell)), glm::ivec3(0), g.dims - 1);
        glm::ivec3 step;
        glm::dvec3 t_max, t_delta;
        for (int k = 0; k < 3; ++k) {
          double d = r.direction[k];
          step[k] = d > 0 ? 1 : -1;
          if (std::abs(d) < 1e-300) {
            t_max[k] = t_delta[k] = 1e300;
            continue;
          }
          double boundary = lo[k] + (c[k] + (d > 0 ? 1 : 0)) * g.cell;
          t_max[k] = (boundary - r.origin[k]) / d;
          t_delta[k] = g.cell / std::abs(d);
        }
        const int max_steps = g.dims.x + g.dims.y + g.dims.z + 3;
        for (int s = 0; s < max_steps; ++s) {
          int64_t col = column_of[g.index(c.x, c.y, c.z)];
          if (col >= 0) entries.emplace_back(int(row), int(col), 1.0);
          int k = t_max.x < t_max.y ? (t_max.x < t_max.z ? 0 : 2) : (t_max.y < t_max.z ? 1 : 2);
          if (t_max[k] >= t1) break;
          c[k] += step[k];
          if (c[k] < 0 || c[k] >= g.dims[k]) break;
          t_max[k] += t_delta[k];
        }
      }
  Eigen::SparseMatrix<double, Eigen::RowMajor> a(Eigen::Index(rows), Eigen::Index(columns.size()));
  a.setFromTriplets(entries.begin(), entries.end());
  return a;
}

Eigen::VectorXd pixel_optical_depths(const ViewSet& views, double delta) {
  size_t rows = 0;
  for (const View& v : views.views) rows += v.mask.alpha.size();
  Eigen::VectorXd b(Eigen::Index(rows), 1);
  size_t row = 0;
  for (const View& v : views.views)
    for (float a : v.mask.alpha) b[Eigen::Index(row++)] = -std::log(1.0 - std::min(double(a), 1.0 - delta));
  return b;
}

Eigen::VectorXd least_squares(const Eigen::SparseMatrix<double, Eigen::RowMajor>& a, const Eigen::VectorXd& b,
                              int max_iterations, double tolerance, int* iterations) {
  Eigen::LeastSquaresConjugateGradient<Eigen::SparseMatrix<double, Eigen::RowMajor>> solver;
  solver.setMaxIterations(max_iterations);
  solver.setTolerance(tolerance);
  solver.compute(a);
  Eigen::VectorXd x = solver.solve(b);
  if (iterations) *iterations = int(solver.iterations());
  return x;
}

DensitySolution solve_density(const ViewSet& views, const DensitySolveParams& params) {
  DensitySolution out;
  out.grid = make_density_grid(views.bounds, params.resolution);
  out.initial = initial_density(out.grid, views);
  std::vector<size_t> columns;
  for (size_t i = 0; i < out.initial.size(); ++i)
    if (out.initial[i] >= params.carve_threshold) columns.push_back(i);
  out.kept_voxels = columns.size();
  if (columns.empty()) return out;
  auto a = projection_matrix(out.grid, views, columns);
  Eigen::VectorXd b = pixel_optical_depths(views);
  Eigen::VectorXd x = least_squares(a, b, params.max_iterations, params.tolerance, &out.iterations);
  x = x.cwiseMax(0.0);  // negative optical depth = empty voxel
  out.relative_residual = (a * x - b).norm() / std::max(b.norm(), 1e-300);
  for (size_t k = 0; k < columns.size(); ++k) out.grid.alpha[columns[k]] = 1.0 - std::exp(-x[Eigen::Index(k)]);
  return out;
}

}  // namespace forest
