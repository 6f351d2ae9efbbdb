// Density volume from silhouette images (Neubert 2012 ch3.3, Neubert et al. 2007).
// 1. Initial density of a voxel: project it into every image, average alpha over its
//    footprint (the bounding rectangle of its 8 projected corners), take the minimum over the
//    images. Voxels below `carve_threshold` are carved (implicit space carving).
// 2. Absorption-only pixel model: theta_p = prod theta_j over the voxels on the pixel's ray
//    (3.2); with x_j = -ln theta_j and b_p = -ln(1 - alpha_p) it is linear, A x = b (3.3), with
//    a_pj = 1 when the ray through pixel p's centre crosses voxel j. [ours] alpha_p is clamped
//    to 1 - delta (delta = 0.01) so b stays finite; the least-squares problem is solved by
//    conjugate gradients on the normal equations (Eigen's LeastSquaresConjugateGradient,
//    i.e. CGLS); negative x are empty voxels (clamped to 0); alpha_j = 1 - exp(-x_j).
#pragma once
#include <vector>

#include <Eigen/SparseCore>

#include "generators/methods/common/image_inputs.h"

namespace forest {

struct DensityGrid {
  glm::ivec3 dims{0};
  glm::dvec3 origin{0.0};
  double cell = 1.0;
  std::vector<double> alpha;  // per voxel, in [0, 1)
  size_t size() const { return size_t(dims.x) * size_t(dims.y) * size_t(dims.z); }
  size_t index(int x, int y, int z) const { return (size_t(z) * size_t(dims.y) + size_t(y)) * size_t(dims.x) + size_t(x); }
  glm::ivec3 cell_of_index(size_t i) const {
    return {int(i % size_t(dims.x)), int((i / size_t(dims.x)) % size_t(dims.y)), int(i / (size_t(dims.x) * size_t(dims.y)))};
  }
  glm::dvec3 corner(glm::ivec3 c) const { return origin + glm::dvec3(c) * cell; }
};

// Cubic cells, n along the longest side of the bounds.
DensityGrid make_density_grid(const Bounds& bounds, int n);

// Step 1 (min over images of the mean alpha of the footprint), per voxel.
std::vector<double> initial_density(const DensityGrid& grid, const ViewSet& views);

// Rows: every pixel of every view (view-major, row-major pixels); columns: the voxels listed
// in `columns` (indices into the grid). Entries are exactly 1 (voxel on the pixel's ray).
Eigen::SparseMatrix<double, Eigen::RowMajor> projection_matrix(const DensityGrid& grid, const ViewSet& views,
                                                               const std::vector<size_t>& columns);

// b_p = -ln(1 - min(alpha_p, 1 - delta)) for every pixel of every view (same row order).
Eigen::VectorXd pixel_optical_depths(const ViewSet& views, double delta = 0.01);

struct DensitySolveParams {
  int resolution = 25;
  double carve_threshold = 0.1;
  int max_iterations = 200;
  double tolerance = 1e-6;
};

struct DensitySolution {
  DensityGrid grid;            // alpha after least squares (0 in carved voxels)
  std::vector<double> initial; // step-1 density
  size_t kept_voxels = 0;      // voxels not carved (the unknowns)
  int iterations = 0;
  double relative_residual = 0.0;  // |A x - b| / |b| with the clamped x
};

// Solves A x = b over the voxels not carved. Bounded by max_iterations.
DensitySolution solve_density(const ViewSet& views, const DensitySolveParams& params);

// The same least squares for given rows (tests: a synthetic volume's exact projections).
Eigen::VectorXd least_squares(const Eigen::SparseMatrix<double, Eigen::RowMajor>& a, const Eigen::VectorXd& b,
                              int max_iterations, double tolerance, int* iterations = nullptr);

}  // namespace forest
