// Species keys shared by the image-based methods (particle-flow, visual-hull):
//   views = "path/to/views.json"   (relative to the species file; see image_inputs.h), or
//   crown = { ... }                (synthetic masks made in memory; see image_synthetic.h)
// -- exactly one of the two -- and the radii and leaves of the tree:
//   tip_radius (m), pipe_exponent, leaf_size (m, 0 = none), leaf_size_jitter, leaf_angle,
//   leaf_angle_jitter (deg), leaves_per_tip, leaves_along.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "generators/core/toml_reader.h"
#include "generators/methods/common/image_inputs.h"
#include "generators/model/model_builder.h"
#include "generators/tree/leaves.h"

namespace forest {

// Keys read by read_image_input and read_image_tree_style, for a method's key list.
#define FOREST_IMAGE_SPECIES_KEYS                                                           \
  "views", "crown", "tip_radius", "pipe_exponent", "leaf_size", "leaf_size_jitter",         \
      "leaf_angle", "leaf_angle_jitter", "leaves_per_tip", "leaves_along"

ViewSet read_image_input(const TomlTable& t);

// Radii and leaves of an image method's tree (the method sets its own defaults).
struct ImageTreeStyle {
  float tip_radius = 0.01f;
  float pipe_exponent = 2.3f;
  LeafParams leaves;
};
ImageTreeStyle read_image_tree_style(const TomlTable& t, const ImageTreeStyle& defaults);

// Pipe radii, twig leaves (dropped where they project onto background); `stats` become the
// model's metadata entry "method_stats".
Skeleton finish_image_tree(TreeGraph graph, const ImageTreeStyle& style, const ViewSet& views,
                           uint64_t seed, nlohmann::json stats);

}  // namespace forest
