// Species preset (TOML, first key `method`) -> TreeModel, through the method's skeleton pass
// and the shared mesher. Every method is deterministic for a given seed.
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "generators/model/tree_model.h"

namespace forest {

class TomlTable;

struct GenerateOptions {
  std::optional<uint64_t> seed;  // overrides the preset's seed when set
  TreeGraph* skeleton = nullptr;  // when set, receives the skeleton the model was meshed from
};

// One modeling method. Each lives in generators/methods/<id>_method.{h,cpp} and has one
// line in the table of methods.cpp.
struct MethodEntry {
  const char* id;
  // `species` is the whole species table (its `method` already checked); paths in it are
  // relative to the species file (species.file()).
  TreeModel (*generate)(const TomlTable& species, const std::string& species_name,
                        const GenerateOptions& options);
  // Built-in preset for `forest generate --method ID`; must run without any input file.
  const char* (*default_species_text)();
  // Writes the method's synthetic inputs (masks, poses, strokes, samples) into `dir`;
  // nullptr when the method needs none.
  void (*make_inputs)(const std::filesystem::path& dir);
};

std::span<const MethodEntry> method_table();

// Reads the species file, runs its method, meshes. Bad file -> InputError (file, line, key).
TreeModel generate_from_species(const std::filesystem::path& species_file,
                                const GenerateOptions& options = {});
// Same, from TOML text (name is used in messages; relative paths resolve against the
// current folder).
TreeModel generate_from_species_text(const std::string& text, const std::string& name,
                                     const GenerateOptions& options = {});

// Method ids known to `forest generate --method`.
std::vector<std::string> method_ids();

// Built-in preset TOML text for a method id (used by `forest generate --method ID` without
// --species); InputError for an unknown id.
std::string default_species_text(const std::string& method);

// `forest make-inputs`: every method's synthetic inputs, each in dir/<method id>/.
void make_inputs(const std::filesystem::path& dir);

}  // namespace forest
