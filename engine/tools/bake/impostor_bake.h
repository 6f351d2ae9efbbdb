// Bakes a model's impostor on the engine's own rasterizer: the model rendered from
// IMPOSTOR_GRID² directions of the upper hemisphere (shaders/impostor_math.h), orthographic,
// each view IMPOSTOR_VIEW_SIZE² pixels with 4× MSAA, three renders per view (coverage, unlit
// albedo, normal and height) assembled into two atlases; then the impostor's Q against full
// detail at every PR table size, from the PR bake's views (Neubert 2012 §7.2's measure), which
// decides at run time where a tree shows its impostor (shaders/impostor_switch.glsl).
#pragma once
#include <cstdint>
#include <vector>

#include "engine/vk/context.h"
#include "generators/model/tree_model.h"

namespace forest {

struct ImpostorBakeStats {
  double atlas_seconds = 0, quality_seconds = 0;
  uint32_t renders = 0;
};

// The atlases of `model` (its q left empty). VkFailure on validation messages.
Impostor bake_impostor_atlases(vk::Context& ctx, const TreeModel& model, ImpostorBakeStats* stats = nullptr);

// Coverage cutoffs the bake tries (Impostor::cutoff).
inline constexpr float kImpostorCutoffs[] = {0.2f, 0.3f, 0.4f, 0.5f};

struct ImpostorQuality {
  std::vector<float> q;  // PR_SIZES, at the cutoff
  float cutoff = 0.5f;   // of kImpostorCutoffs, the best mean Q over the sizes
};

// Q of model.impostor against the full-detail model at pr_size(size0, b), b < PR_SIZES: pixel
// counts pooled over `views` PR bake views (pr_views), each size rendered in the frame of size
// 0 from farther away; at each of kImpostorCutoffs, the best one kept.
ImpostorQuality measure_impostor_quality(vk::Context& ctx, const TreeModel& model, uint32_t views, uint32_t size0,
                                         ImpostorBakeStats* stats = nullptr);

// Both: model.impostor with its atlases and qualities.
void attach_impostor(vk::Context& ctx, TreeModel& model, uint32_t views, uint32_t size0,
                     ImpostorBakeStats* stats = nullptr);

}  // namespace forest
