// Learning plantons and their transitions from sample trees (Wang 2006 §5): k-means
// initialization with the distance D of eq. (1), then hard-assignment EM — estimate the
// Gaussians, child counts and transitions from the current clusters (pooled over all
// samples, Wang 2006 §5.2), relabel every sample by tree max-product, move organs whose error exceeds
// e_max into new plantons — until the labels repeat.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "generators/methods/plantons/plantons_model.h"

namespace forest {

struct LearnParams {
  std::array<int, kOrganTypes> initial_plantons{8, 2};  // k of k-means per organ type
  // An organ whose D to its planton's mean, per parameter (D / dim, in units of the pooled
  // variance), exceeds e_max starts a new planton. 16 (4 pooled standard deviations) splits
  // off real outliers only: a Gaussian cluster's own tail (one leaf parameter: P(z² > 16) =
  // 6e-5) stays in its planton.
  double e_max = 16.0;
  double regularization = 1e-3;  // λ added to the covariances (z units)
  int max_iterations = 30;
  int kmeans_restarts = 4;
  uint64_t seed = 1;
};

struct LearnResult {
  PlantonModel model;                          // with exemplars; damped when it had to be
  std::vector<std::vector<uint32_t>> labels;   // per sample, per organ
  size_t plantons_after_kmeans = 0;
  int iterations = 0;                          // EM iterations run
  bool converged = false;                      // labels repeated (else max_iterations hit)
  double spectral_radius_before_damping = 0.0;
  double spectral_radius = 0.0;
};

// Deterministic for (samples, params). InputError when there are no samples or organs.
LearnResult learn_plantons(const std::vector<OrganTree>& samples, const LearnParams& params);

// k-means over one type's organs in z coordinates (k-means++ seeding, best of `restarts`):
// cluster index per point.
std::vector<uint32_t> kmeans(const std::vector<std::vector<double>>& points, int k, int restarts,
                             uint64_t seed);

// Adjusted Rand index of two labellings of the same items (1 = identical partitions).
double adjusted_rand_index(const std::vector<uint32_t>& a, const std::vector<uint32_t>& b);

}  // namespace forest
