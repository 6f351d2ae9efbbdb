// Method `plantons` (Wang 2006): trees synthesized from a two-level
// statistical model — plantons (clusters of similar organs) and the transitions between
// them — learned from sample trees by `forest learn` (plantons_learn.h). A preset names the
// learned model file; synthesis (plantons_synth.h) builds an organ tree that is turned into
// a TreeGraph and meshed like every other method.
#pragma once
#include <string>

#include "generators/core/toml_reader.h"
#include "generators/species/registry.h"

namespace forest {

TreeModel generate_plantons(const TomlTable& root, const std::string& species_name,
                            const GenerateOptions& options);

// The built-in preset: learns from three ground-truth trees in-process, then synthesizes.
const char* plantons_default_species_text();

}  // namespace forest
