// Species cache: a species spec ([[species]] preset + seed) is generated and baked once,
// then loaded from `<cache dir>/<preset stem>-<key>.glb`. The key hashes what the baked bytes
// depend on: the preset file's text, the seed, the bake settings and kSpeciesCacheVersion
// (bumped by hand whenever a generator or the bake changes its output).
// Writes are atomic (temporary file + rename), so concurrent runs at worst bake twice.
#pragma once
#include <filesystem>
#include <functional>
#include <string>

#include "engine/scene/scene.h"
#include "generators/model/tree_model.h"

namespace forest::vk {
struct Context;
}

namespace forest {

// Bumped whenever a generator or the bake changes what a spec produces.
constexpr int kSpeciesCacheVersion = 8;  // 8: impostors; 3: bark textures, physical bark uv, seam-keeping LODs; 4: crown depths; 5: PR tables per
                                         // projected size; 6: λ_opt = λ_Cook below the first measured λ;
                                         // 7: structural branch LODs

// $FOREST_CACHE, else $XDG_CACHE_HOME/forest, else $HOME/.cache/forest, else build-less
// fallback ".forest-cache" in the current folder.
std::filesystem::path default_cache_dir();

// 32 hex digits. InputError when the preset cannot be read.
std::string species_cache_key(const SpeciesDesc& species, const BakeDesc& bake);

struct CachedSpecies {
  TreeModel model;
  bool hit = false;                // loaded from the cache, nothing generated
  std::filesystem::path file;      // the cached .glb
  double generate_seconds = 0, bake_seconds = 0;
};

// Loads the baked model of a preset species from the cache, or generates + bakes + stores
// it. `ctx`: the device that measures the PR tables on a miss (nullptr: a context is
// created for the bake and destroyed after it).
CachedSpecies load_or_bake_species(const SpeciesDesc& species, const BakeDesc& bake,
                                   const std::filesystem::path& cache_dir, vk::Context* ctx = nullptr);

// The species cache as build_scene()'s source of preset models: how the app layer asks for
// baked models (baking on first use).
struct SpeciesCacheOptions {
  std::filesystem::path dir;  // empty: default_cache_dir()
  vk::Context* ctx = nullptr;  // device for bakes on a cache miss (nullptr: own context)
  std::function<void(const std::string&)> log;  // one line per species loaded or baked
};
struct SpeciesCacheCounts {
  uint32_t hits = 0, misses = 0;  // species loaded from / added to the cache
};
// `counts`, when given, must outlive the source.
SpeciesSource cached_species_source(const SpeciesCacheOptions& options, SpeciesCacheCounts* counts = nullptr);

}  // namespace forest
