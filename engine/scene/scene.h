// A loaded scene: terrain, one model per species and every tree instance, ready to upload.
// Built once; the frame loop never walks the instances on the CPU.
#pragma once
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "engine/scene/scene_file.h"
#include "engine/scene/terrain.h"
#include "generators/model/tree_model.h"
#include "gpu_types.h"

namespace forest {

// Where build_scene() gets the model of a [[species]] preset (one with `model = FILE` is
// loaded from that file). The scene layer never bakes: a baked model comes from a source the
// app layer hands in, e.g. the species cache of engine/tools/bake/species_cache.h.
using SpeciesSource = std::function<TreeModel(const SpeciesDesc& species, const BakeDesc& bake)>;

struct SceneBuildOptions {
  SpeciesSource species;  // empty: generate in-process, unbaked, nothing written
};

struct Scene {
  SceneDesc desc;
  Terrain terrain;
  std::vector<TreeModel> models;           // index = species index
  std::vector<gpu::Instance> instances;
  uint32_t placement_shortfall = 0;        // trees of placement.count that found no room
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
