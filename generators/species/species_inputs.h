// The files a species preset is made from: the preset itself and every file it names, and
// the files those name in turn (a visual hull's views.json names its mask PNGs, a particle
// flow view names its attractor SVG). The species cache hashes their contents into its key,
// so editing a mask makes a new tree instead of reusing the old one.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace forest {

struct SpeciesInput {
  std::filesystem::path file;  // as found: the referring file's folder / the string
  std::string name;            // relative to the preset's folder ("../inputs/x/view0.png")
  std::string bytes;           // the file's contents
};

// The preset first, then every file reached from it, each once, in the order found (a
// deterministic walk). A string value of the preset (TOML) or of a referenced .json / .toml
// counts as a reference when it names an existing regular file relative to that file's
// folder, whatever its key: no method has to declare its inputs. Referenced files that do not
// parse are still hashed (the generator then reports them). InputError when the preset
// cannot be read.
std::vector<SpeciesInput> species_inputs(const std::filesystem::path& preset);

}  // namespace forest
