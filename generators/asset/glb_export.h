// Client files of a model, for viewers and DCC tools rather than the engine (forest export):
// one .glb per branch LOD, `<out>.glb` (LOD0) and `<out stem>_LOD1.glb` … `_LODn.glb`, each a
// whole tree (its bark level and every leaf) under a root node `<name>_LOD<i>` whose extras
// give the level, its error in metres and the screen coverage below which it may replace
// LOD0. Nothing else is in them: no hull, no impostor atlases, no bake data (extras.forest),
// so no client shows the engine's helpers as geometry (Blender imports every node of a file,
// in a scene or not). Leaves: EXT_mesh_gpu_instancing with the per-leaf colour as
// `_COLOR_0` (three.js, Blender 4, Babylon.js), or with `flatten` one ordinary mesh with the
// colour as vertex colour COLOR_0 (Blender 3, Godot 4 and any client without the extension).
#pragma once
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "generators/model/tree_model.h"

namespace forest {

struct ExportOptions {
  bool flatten = false;
  // Screen coverage thresholds are for this frame height and projected error (the engine's
  // default [render] lod_error_pixels = 1 and a 1080-line screen).
  float error_pixels = 1.0f;
  float screen_height = 1080.0f;
  std::function<void(double)> progress;  // fraction of the files written (0..1), when set
};

struct ExportedLod {
  std::filesystem::path file;
  std::string node;          // root node name, <name>_LOD<i>
  uint32_t level = 0;
  float error = 0.0f;        // metres
  float screen_coverage = 1.0f;  // bounding-sphere diameter ÷ screen height below which it may be used
  size_t branch_triangles = 0, leaves = 0, leaf_triangles = 0;
};

// Writes the files (atomically, each; on a failure the ones already written are removed) and
// says what is in them. `name`: the node prefix
// (default: the out file's stem).
std::vector<ExportedLod> export_model(const TreeModel& model, const std::filesystem::path& out,
                                      const ExportOptions& options = {});

}  // namespace forest
