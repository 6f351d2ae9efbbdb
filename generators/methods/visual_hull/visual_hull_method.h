// Method `visual-hull` (Shlyakhter 2001): silhouette masks + camera poses ->
// visual hull -> skeleton from the hull's medial axis -> open L-system grown and pruned
// inside the hull -> leaves (dropped where they project onto background) -> mesh.
#pragma once
#include <filesystem>
#include <string>

#include "generators/core/toml_reader.h"
#include "generators/species/registry.h"

namespace forest {

TreeModel generate_visual_hull(const TomlTable& root, const std::string& species_name,
                               const GenerateOptions& options);
// Built-in preset: a synthetic lobed crown rendered into 8 perspective masks in memory.
const char* visual_hull_default_species_text();
// dir/ellipsoid and dir/cone: views.json + 8 perspective 128x128 masks each.
void visual_hull_make_inputs(const std::filesystem::path& dir);

}  // namespace forest
