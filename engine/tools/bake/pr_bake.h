// Measures a model's pruning tables with Precision/Recall on the engine's own rasterizer
// (Neubert 2012 §7.2): coverage of the full model vs the model pruned to a prefix λ of its
// (priority-ordered) leaves with leaf area scale s, from several views, counted on the GPU.
#pragma once
#include <functional>
#include <vector>

#include "engine/render/renderer.h"
#include "generators/asset/pr_tables.h"

namespace forest {

// The sizes whose s is searched by default (PrBakeOptions::searched_sizes), bit b for size b.
inline constexpr uint32_t kSearchedSizes = (1u << PR_SIZES) - 1u;

struct PrBakeOptions {
  // Projected size of the tables' size 0, in pixels across the bounding sphere; the tables
  // hold it and PR_SIZES − 1 halvings, all measured from the same renders (lattices).
  uint32_t size0 = 512;
  uint32_t views = 6;         // azimuths around the model, alternating two elevations
  uint32_t scale_candidates = 12;  // s grid per λ, geometric in [1, 1.5/λ], plus 1/λ
  // Bracket search over the s grid, exploiting that Q(λ, s) is unimodal in s (it trades
  // recall for precision): about half the renders of trying every grid value. false: every
  // grid value (the reference the search is tested against).
  bool search_scale = true;
  // Sizes whose s_opt is searched, bit b for size b. The others take the best s among the
  // points measured for these (every render counts every size): 1 is the single-size bake of
  // old, for comparisons.
  uint32_t searched_sizes = kSearchedSizes;
  std::function<void(double)> progress;  // fraction done, for a progress bar
};

// Where the time of a measurement went (seconds, wall clock) and how much was rendered.
struct PrBakeStats {
  double reference_seconds = 0;  // per-view full-detail (and branch) coverage
  double compare_seconds = 0;    // pruned renders + pixel counts + count readback
  uint32_t renders = 0;          // pruned coverage renders (each counted on the GPU)
  uint32_t submits = 0;
};

// One measured point of the PR diagram, at every size.
struct PrSample {
  float lambda = 0, scale = 0;
  PrSizes pr;
};

struct PrMeasurement {
  PrTables tables;
  std::vector<PrSample> samples;  // every (λ, s) measured, summed over views
  PrBakeStats stats;
};

// The bake's camera for one view: the bounding sphere centred, `size0` pixels across in a
// square frame of `resolution` pixels (fov 30°).
CameraDesc pr_view_camera(glm::vec4 bounding_sphere, float azimuth, float elevation, uint32_t size0, uint32_t resolution);
// The bake's `views` cameras: azimuths around the model, alternating elevations of 10° and
// 35°, the sphere `size` pixels across in a square frame of `resolution` pixels.
std::vector<CameraDesc> pr_views(glm::vec4 bounding_sphere, uint32_t views, uint32_t size, uint32_t resolution);
// Pixels of the square coverage render for size0: the sphere and a border of two pixels.
uint32_t pr_render_resolution(uint32_t size0);

// `model`'s leaves must already be in priority order (a prefix is what survives).
PrMeasurement measure_pr_tables(vk::Context& ctx, const TreeModel& model, const PrBakeOptions& options = {});

// The s values tried at detail λ > 0: the geometric grid and 1/λ, ascending, distinct.
std::vector<float> scale_grid(float lambda, uint32_t candidates);

// Smallest λ on a 1/1000 grid below `upper` whose interpolated q_opt (S_SAMPLES values at
// λ = i/(S_SAMPLES − 1)) reaches `target`; `upper` when none does (Neubert 2012 §7.2.5).
float smallest_lambda_reaching(const std::vector<float>& q_opt, double target, float upper);

// Pool-adjacent-violators: the closest non-increasing sequence (least squares).
std::vector<float> non_increasing(std::vector<float> v);

}  // namespace forest
