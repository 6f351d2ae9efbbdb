// Species cache: a species spec ([[species]] preset + seed) is generated and baked once,
// then loaded from `<cache dir>/<preset stem>-<key>.glb`. The key hashes everything the baked
// bytes depend on: the contents of the preset and of every file it names (species_inputs.h:
// masks, strokes, drawings, sample trees, plantons models), the seed, the bake settings and
// the build identity of the generator and bake code (build_identity.h), so no entry outlives
// the inputs or the code that made it. Beside each entry, a record (cache_record.h) says what
// it was made from and which device measured it. Writes are atomic (temporary file +
// rename), so concurrent runs, on one machine or many sharing the folder, at worst bake twice
// and leave one complete entry.
#pragma once
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "engine/scene/scene.h"
#include "engine/tools/bake/cache_record.h"
#include "generators/model/tree_model.h"

namespace forest::vk {
struct Context;
}

namespace forest {

// $FOREST_CACHE, else $XDG_CACHE_HOME/forest, else $HOME/.cache/forest, else build-less
// fallback ".forest-cache" in the current folder.
std::filesystem::path default_cache_dir();

struct SpeciesKey {
  std::string key;                      // 32 hex digits
  std::vector<CacheInputRecord> inputs;  // what it hashed, the preset first
};
// InputError when the preset cannot be read.
SpeciesKey species_key(const SpeciesDesc& species, const BakeDesc& bake);
std::string species_cache_key(const SpeciesDesc& species, const BakeDesc& bake);
// `<cache dir>/<preset stem>-<key>.glb`.
std::filesystem::path species_cache_file(const SpeciesDesc& species, const std::string& key,
                                         const std::filesystem::path& cache_dir);

struct CachedSpecies {
  TreeModel model;
  bool hit = false;                // loaded from the cache, nothing generated
  std::filesystem::path file;      // the cached .glb
  double generate_seconds = 0, bake_seconds = 0;
};

// Loads the baked model of a preset species from the cache, or generates + bakes + stores
// it. `ctx`: the device that measures the PR tables on a miss (nullptr: a context is
// created for the bake and destroyed after it).
// `progress`, when set, hears the bake's fraction done (0..1) on a miss.
CachedSpecies load_or_bake_species(const SpeciesDesc& species, const BakeDesc& bake,
                                   const std::filesystem::path& cache_dir, vk::Context* ctx = nullptr,
                                   const std::function<void(double)>& progress = {});

// The species cache as build_scene()'s source of preset models: how the app layer asks for
// baked models (baking on first use).
struct SpeciesCacheOptions {
  std::filesystem::path dir;  // empty: default_cache_dir()
  vk::Context* ctx = nullptr;  // device for bakes on a cache miss (nullptr: own context)
  std::function<void(const std::string&)> log;  // one line per species loaded or baked
  // A bake's progress on a miss: the species and the fraction done (0..1).
  std::function<void(const SpeciesDesc&, double)> progress;
};
struct SpeciesCacheCounts {
  uint32_t hits = 0, misses = 0;  // species loaded from / added to the cache
};
// `counts`, when given, must outlive the source.
SpeciesSource cached_species_source(const SpeciesCacheOptions& options, SpeciesCacheCounts* counts = nullptr);

}  // namespace forest
