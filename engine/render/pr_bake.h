// Measures a model's pruning tables with Precision/Recall on the engine's own rasterizer
// (seed 000 §7.2): coverage of the full model vs the model pruned to a prefix λ of its
// (priority-ordered) leaves with leaf area scale s, from several views, counted on the GPU.
#pragma once
#include <functional>
#include <vector>

#include "engine/render/renderer.h"
#include "generators/bake/pr_tables.h"

namespace forest {

struct PrBakeOptions {
  uint32_t resolution = 256;  // pixels of each square coverage render
  uint32_t views = 6;         // azimuths around the model, alternating two elevations
  uint32_t scale_candidates = 12;  // s values tried per λ, geometric in [1, 1.5/λ], plus 1/λ
  std::function<void(double)> progress;  // fraction done, for a progress bar
};

// One measured point of the PR diagram.
struct PrSample {
  float lambda = 0, scale = 0;
  PrResult pr;
};

struct PrMeasurement {
  PrTables tables;
  std::vector<PrSample> samples;  // every (λ, s) measured, summed over views
};

// `model`'s leaves must already be in priority order (a prefix is what survives).
PrMeasurement measure_pr_tables(vk::Context& ctx, const TreeModel& model, const PrBakeOptions& options = {});

// Pool-adjacent-violators: the closest non-increasing sequence (least squares).
std::vector<float> non_increasing(std::vector<float> v);

}  // namespace forest
