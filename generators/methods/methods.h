// Species preset (TOML, first key `method`) -> TreeModel, through the method's skeleton pass
// and the shared mesher. Every method is deterministic for a given seed.
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "generators/tree/tree_model.h"

namespace forest {

struct GenerateOptions {
  std::optional<uint64_t> seed;  // overrides the preset's seed when set
};

// Reads the species file, runs its method, meshes. Bad file -> InputError (file, line, key).
TreeModel generate_from_species(const std::filesystem::path& species_file,
                                const GenerateOptions& options = {});
// Same, from TOML text (name is used in messages).
TreeModel generate_from_species_text(const std::string& text, const std::string& name,
                                     const GenerateOptions& options = {});

// Method ids known to `forest generate --method`.
std::vector<std::string> method_ids();

}  // namespace forest

namespace forest {
// Built-in preset TOML text for a method id (used by `forest generate --method ID` without
// --species); InputError for an unknown id.
std::string default_species_text(const std::string& method);
}  // namespace forest
