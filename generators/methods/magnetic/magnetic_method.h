// Method `magnetic` (Xu 2015 ch7): space-filling magnetic curves as a tree. mode = "2d" is
// the thesis' Klimt-style picture as a planar relief model (curves in the x–y plane as
// tubes, depth = tube thickness); mode = "3d" [ours] flies the particles through a 3D field.
#pragma once
#include <filesystem>
#include <optional>
#include <string>

#include "generators/core/toml_reader.h"
#include "generators/methods/magnetic/magnetic_curves.h"
#include "generators/species/registry.h"

namespace forest {

struct MagneticSpecies {
  SpaceFillParams fill;
  MagneticField field;
  double scale = 0.015;  // meters per simulation unit
};
MagneticSpecies read_magnetic_species(const TomlTable& t);

// Curves -> skeleton: curve 0 starts at the origin, children hang off their release point;
// TreeNode::order = curve depth.
TreeGraph magnetic_tree(const MagneticResult& r, const MagneticSpecies& s);

// The method's registry entry (species keys, skeleton pass, built-in preset, inputs).
extern const MethodEntry kMagneticMethod;

// For `forest generate --method magnetic --svg out.svg` (or --species FILE): the SVG of the
// curves the species makes with that seed. `text` is the species TOML, `name` its file name.
std::string magnetic_svg_from_species_text(const std::string& text, const std::string& name,
                                           std::optional<uint64_t> seed);

}  // namespace forest
