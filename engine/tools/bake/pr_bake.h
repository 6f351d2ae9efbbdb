// Measures a model's pruning tables with Precision/Recall on the engine's own rasterizer
// (Neubert 2012 §7.2): coverage of the full model vs the model pruned to a prefix λ of its
// (priority-ordered) leaves with leaf area scale s, from several views, counted on the GPU.
#pragma once
#include <functional>
#include <vector>

#include "engine/render/renderer.h"
#include "generators/asset/pr_tables.h"

namespace forest {

struct PrBakeOptions {
  uint32_t resolution = 256;  // pixels of each square coverage render
  uint32_t views = 6;         // azimuths around the model, alternating two elevations
  uint32_t scale_candidates = 12;  // s grid per λ, geometric in [1, 1.5/λ], plus 1/λ
  // Bracket search over the s grid, exploiting that Q(λ, s) is unimodal in s (it trades
  // recall for precision): about half the renders of trying every grid value.
  bool search_scale = true;
  // All renders of a search round in one submit, branches drawn once per view
  // (Renderer::compare_coverage). false: one submit per render with the branches redrawn
  // each time — the original path, kept as the reference for tests and bake_bench.
  bool batched = true;
  std::function<void(double)> progress;  // fraction done, for a progress bar
};

// Where the time of a measurement went (seconds, wall clock) and how much was rendered.
struct PrBakeStats {
  double reference_seconds = 0;  // per-view full-detail (and branch) coverage
  double compare_seconds = 0;    // pruned renders + pixel counts + count readback
  uint32_t renders = 0;          // pruned coverage renders (each counted on the GPU)
  uint32_t submits = 0;
};

// One measured point of the PR diagram.
struct PrSample {
  float lambda = 0, scale = 0;
  PrResult pr;
};

struct PrMeasurement {
  PrTables tables;
  std::vector<PrSample> samples;  // every (λ, s) measured, summed over views
  PrBakeStats stats;
};

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
