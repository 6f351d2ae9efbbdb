// Species preset (TOML, first key `method`) -> TreeModel: the registry checks the keys, reads
// name, seed, the shared look and foliage keys, runs the method's skeleton pass, places the
// foliage (tree/foliage.h) and hands the skeleton to the shared model stage (model_builder.h).
// Every method is deterministic for its seed.
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "generators/model/model_builder.h"

namespace forest {

class TomlTable;

struct GenerateOptions {
  std::optional<uint64_t> seed;  // overrides the preset's seed when set
  TreeGraph* skeleton = nullptr;  // when set, receives the skeleton the model was meshed from
};

// Keys of every species file besides the method's own, the look keys (kLookKeys), the
// foliage keys (kFoliageKeys) and the [habit] ranges (kHabitKeys, tree/habit_ranges.h; the
// registry checks them, and no method reads them).
inline constexpr std::string_view kCommonSpeciesKeys[] = {"method", "name", "seed"};

// One modeling method. Each lives in generators/methods/<id>/, exports its entry from
// <id>_method.h and has one line in the table of registry.cpp (docs/adding-a-method.md).
struct MethodEntry {
  const char* id;
  // The method's own top-level keys; the registry accepts these, kCommonSpeciesKeys and
  // kLookKeys and kFoliageKeys and refuses every other key before the skeleton pass runs.
  std::span<const std::string_view> keys;
  // The skeleton pass: all of the method's randomness, from `seed` only. `species` is the
  // whole species table (keys already checked); paths in it are relative to the species
  // file (species.file()). Must not read the look or foliage keys, nor place leaves: the
  // shared foliage stage (tree/foliage.h) replaces graph.leaves after this pass.
  Skeleton (*skeleton)(const TomlTable& species, uint64_t seed);
  // Built-in preset for `forest generate --method ID`; must run without any input file.
  const char* (*default_species_text)();
  // Writes the method's synthetic inputs (masks, poses, strokes, samples) into `dir`;
  // nullptr when the method needs none.
  void (*make_inputs)(const std::filesystem::path& dir);
};

std::span<const MethodEntry* const> method_table();

// Reads the species file, runs its method's skeleton pass and the model stage.
// Bad file -> InputError (file, line, key).
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
