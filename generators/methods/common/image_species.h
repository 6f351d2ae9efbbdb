// Species keys shared by the image-based methods (particle-flow, visual-hull):
//   views = "path/to/views.json"   (relative to the species file; see image_inputs.h), or
//   crown = { ... }                (synthetic masks made in memory; see image_synthetic.h)
// -- exactly one of the two -- and the radii of the tree: tip_radius (m), pipe_exponent.
// Foliage comes from the shared foliage stage, kept to where every view's mask shows the
// crown.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "generators/core/toml_reader.h"
#include "generators/methods/common/image_inputs.h"
#include "generators/model/model_builder.h"

namespace forest {

// Keys read by read_image_input and read_image_tree_style, for a method's key list.
#define FOREST_IMAGE_SPECIES_KEYS "views", "crown", "tip_radius", "pipe_exponent"

ViewSet read_image_input(const TomlTable& t);

// Radii of an image method's tree (the method sets its own defaults).
struct ImageTreeStyle {
  float tip_radius = 0.01f;
  float pipe_exponent = 2.3f;
};
ImageTreeStyle read_image_tree_style(const TomlTable& t, const ImageTreeStyle& defaults);

// Pipe radii, and a foliage filter that drops elements projecting onto background in any
// view; `stats` become the model's metadata entry "method_stats".
Skeleton finish_image_tree(TreeGraph graph, const ImageTreeStyle& style, const ViewSet& views,
                           nlohmann::json stats);

}  // namespace forest
