// Method `sketch-mrf` (Neubert 2012 ch4, after Chen et al. 2008): a 2D stroke drawing (+ optional
// crown curve) -> template choice from the database (L_c + L_b) -> depths by the factor
// graph (K! label hypotheses, ICM, EM over Omega) -> propagation of replication blocks
// bounded by the crown -> pipe-model radii, leaves of the template -> mesh.
#pragma once
#include <filesystem>
#include <string>

#include "generators/core/toml_reader.h"
#include "generators/species/registry.h"
#include "generators/methods/common/strokes_io.h"

namespace forest {

TreeModel generate_sketch_mrf(const TomlTable& species, const std::string& species_name,
                              const GenerateOptions& options);
const char* sketch_mrf_default_species_text();
// Writes dir/maple.json, dir/pine.json (strokes with ground-truth depths and a crown
// curve) and dir/maple.svg (the same strokes as SVG polylines).
void sketch_mrf_make_inputs(const std::filesystem::path& dir);

// The synthetic sketches: template `name` seen from `view`, `generations` stroke levels.
Drawing sketch_mrf_synthetic_drawing(const std::string& template_name, int view, int generations);

}  // namespace forest
