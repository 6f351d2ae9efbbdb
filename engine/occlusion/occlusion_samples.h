// The points whose visibility gives a tree's occlusion factor f (Neubert 2012 §7.4): the baked
// hull samples (TreeModel::bake.hull), or, for a model that was
// never baked, points spread over the ellipsoid spanning its leaves (the crown; the bounding
// sphere for a leafless model). A crown ellipsoid rather than the bounding sphere [ours]: the
// sphere reaches below the ground and past the crown, where terrain and neighbours would
// hide samples of a tree that is in plain view.
#pragma once
#include <cstdint>
#include <vector>

#include "generators/model/tree_model.h"
#include "gpu_types.h"

namespace forest {

constexpr uint32_t kEllipsoidOcclusionSamples = 48;

struct OcclusionSamples {
  std::vector<gpu::HullSample> samples;  // model space
  // Model-space distance a sample moves toward the camera before it is tested: the hull's
  // metaball radius (leaves reach about that far outside it).
  float margin = 0.0f;
  bool from_hull = false;
};

// The hull samples were validated when the asset was read; std::invalid_argument when the
// model's are inconsistent (normals of another count, or zero).
OcclusionSamples occlusion_samples(const TreeModel& model);

}  // namespace forest
