// Method `particle-flow` (Neubert 2012 ch3, after Neubert et al. 2007): >= 2 silhouette masks (+ attractor
// polylines: trunk and first-order branches drawn on each image) -> density volume by least
// squares -> particles seeded by density flow to the base, merging into branches -> graph
// -> pipe radii, leaves, mesh.
#pragma once
#include <filesystem>
#include <string>

#include "generators/core/toml_reader.h"
#include "generators/species/registry.h"

namespace forest {

TreeModel generate_particle_flow(const TomlTable& root, const std::string& species_name,
                                 const GenerateOptions& options);
// Built-in preset: two orthographic 128x128 masks of a synthetic crown, made in memory.
const char* particle_flow_default_species_text();
// dir/oak and dir/poplar: views.json (2 orthographic views at 90 degrees, attractor
// polylines inline) + two 128x128 masks each, and views_svg.json with the same attractors in
// view0_attractors.svg / view1_attractors.svg (pixel coordinates).
void particle_flow_make_inputs(const std::filesystem::path& dir);

}  // namespace forest
