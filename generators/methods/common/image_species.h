// Species keys shared by the image-based methods (particle-flow, visual-hull):
//   views = "path/to/views.json"   (relative to the species file; see image_inputs.h), or
//   crown = { ... }                (synthetic masks made in memory; see image_synthetic.h)
// -- exactly one of the two -- and the look of the tree:
//   tip_radius (m), pipe_exponent, leaf_size (m, 0 = none), leaf_size_jitter, leaf_angle,
//   leaf_angle_jitter (deg), leaves_per_tip, leaves_along, ring_sides_min, ring_sides_max,
//   bark_color, leaf_color (linear RGB).
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "generators/core/toml_reader.h"
#include "generators/methods/common/image_inputs.h"
#include "generators/model/model_builder.h"
#include "generators/tree/leaves.h"

namespace forest {

// Keys read by read_image_input and read_tree_look (for check_keys lists).
inline constexpr std::string_view kImageInputKeys[] = {"views", "crown"};
inline constexpr std::string_view kTreeLookKeys[] = {
    "tip_radius", "pipe_exponent", "leaf_size", "leaf_size_jitter", "leaf_angle",
    "leaf_angle_jitter", "leaves_per_tip", "leaves_along", "ring_sides_min", "ring_sides_max",
    "bark_color", "leaf_color"};

// Fails on any key that is neither in `own` nor shared.
void check_image_species_keys(const TomlTable& t, std::initializer_list<std::string_view> own);

ViewSet read_image_input(const TomlTable& t);

struct TreeLook {
  float tip_radius = 0.01f;
  float pipe_exponent = 2.3f;
  LeafParams leaves;
  MesherParams mesher;
  glm::vec3 bark_color{0.30f, 0.22f, 0.15f};
  glm::vec3 leaf_color{0.18f, 0.35f, 0.08f};
};
TreeLook read_tree_look(const TomlTable& t, const TreeLook& defaults);

// Pipe radii, twig leaves (dropped where they project onto background), mesh and metadata.
// `extra` is merged into the model's metadata under "method_stats".
TreeModel finish_image_tree(TreeGraph graph, const TreeLook& look, const ViewSet& views,
                            const TomlTable& root, const std::string& method,
                            const std::string& species_name, uint64_t seed,
                            const nlohmann::json& extra);

}  // namespace forest
