// Method `lsystem` (Neubert 2012 ch2): a species file names an axiom, productions and turtle
// parameters; the skeleton is the turtle's drawing of the rewritten string, radii follow the
// pipe model, leaves come from L symbols or sit on the terminal twigs.
#pragma once
#include <string>

#include "generators/core/toml_reader.h"
#include "generators/species/registry.h"

namespace forest {

// `root` is the species table (its `method` already checked to be "lsystem").
TreeModel generate_lsystem(const TomlTable& root, const std::string& species_name,
                           const GenerateOptions& options);

// The built-in preset: the text of scenes/species/fig2_1.toml.
const char* lsystem_default_species_text();

}  // namespace forest
