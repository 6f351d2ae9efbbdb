// A loaded scene: terrain, one model per species and every tree instance, ready to upload.
// Built once; the frame loop never walks the instances on the CPU.
#pragma once
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "engine/scene/scene_file.h"
#include "engine/scene/terrain.h"
#include "generators/tree/tree_model.h"
#include "gpu_types.h"

namespace forest {

namespace vk {
struct Context;
}

// How build_scene() turns [[species]] presets into models.
struct SceneBuildOptions {
  // false: generate presets in-process (unbaked, nothing written). true: generate + bake on
  // first use, cached by content hash in cache_dir (see species_cache.h).
  bool use_cache = false;
  std::filesystem::path cache_dir;  // empty: default_cache_dir()
  vk::Context* ctx = nullptr;       // device for bakes on a cache miss (nullptr: own context)
  std::function<void(const std::string&)> log;  // one line per species loaded or baked
};

struct Scene {
  SceneDesc desc;
  Terrain terrain;
  std::vector<TreeModel> models;           // index = species index
  std::vector<gpu::Instance> instances;
  uint32_t placement_shortfall = 0;        // trees of placement.count that found no room
  uint32_t cache_hits = 0, cache_misses = 0;  // species loaded from / added to the cache
};

// Generates (or loads) the species models and places the trees. InputError on bad files.
Scene build_scene(const SceneDesc& desc, const SceneBuildOptions& options = {});

// Every instance at full detail (LOD0 bark + every leaf card), no pruning, no culling: the
// size of the forest the renderer avoids drawing. `vertices` counts each mesh's distinct
// vertices; input assembly processes 3 per triangle (`triangles`, indexed lists).
struct FullDetailSize {
  uint64_t vertices = 0, triangles = 0;
};
FullDetailSize full_detail_size(const Scene& scene);

// Poisson-disc-like dart throwing on the terrain: deterministic for placement.seed.
std::vector<gpu::Instance> place_trees(const SceneDesc& desc, const Terrain& terrain,
                                       uint32_t* shortfall = nullptr);

}  // namespace forest
