// Method `mgv` (Xu 2015 ch5–6): species file -> MgvParams -> grow_mgv (mgv_grow.h) ->
// skeleton style (radii w = s^ζ or pipe model, leaves) -> build_tree_model.
#pragma once
#include <string>

#include "generators/core/toml_reader.h"
#include "generators/species/registry.h"
#include "generators/methods/mgv/mgv_grow.h"

namespace forest {

// Reads the method's keys (not the skeleton style); errors name file, line and key.
MgvParams read_mgv_params(const TomlTable& t);

TreeModel generate_mgv(const TomlTable& root, const std::string& species_name,
                       const GenerateOptions& options);

// The built-in preset: the text of scenes/species/mgv_c.toml.
const char* mgv_default_species_text();

}  // namespace forest
