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

// The method's registry entry (species keys, skeleton pass, built-in preset, inputs).
extern const MethodEntry kSketchMrfMethod;

// The synthetic sketches: template `name` seen from `view`, `generations` stroke levels.
Drawing sketch_mrf_synthetic_drawing(const std::string& template_name, int view, int generations);

}  // namespace forest
