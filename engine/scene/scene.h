// A loaded scene: terrain, one model per species and every tree instance, ready to upload.
// Built once; the frame loop never walks the instances on the CPU.
#pragma once
#include <vector>

#include "engine/scene/scene_file.h"
#include "engine/scene/terrain.h"
#include "generators/tree/tree_model.h"
#include "gpu_types.h"

namespace forest {

struct Scene {
  SceneDesc desc;
  Terrain terrain;
  std::vector<TreeModel> models;           // index = species index
  std::vector<gpu::Instance> instances;
  uint32_t placement_shortfall = 0;        // trees of placement.count that found no room
};

// Generates (or loads) the species models and places the trees. InputError on bad files.
Scene build_scene(const SceneDesc& desc);

// Poisson-disc-like dart throwing on the terrain: deterministic for placement.seed.
std::vector<gpu::Instance> place_trees(const SceneDesc& desc, const Terrain& terrain,
                                       uint32_t* shortfall = nullptr);

}  // namespace forest
