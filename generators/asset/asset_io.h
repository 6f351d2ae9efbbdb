// TreeModel <-> glTF 2.0 binary (.glb). Leaves are instances of one leaf card mesh through
// EXT_mesh_gpu_instancing; the root's extras.forest carries the model's metadata.
#pragma once
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "generators/model/tree_model.h"

namespace forest {

// Deterministic: the same model gives byte-identical output.
// How encode_glb writes: the defaults make the engine's asset (what decode_glb reads back);
// glb_export.h changes them for client files.
struct GlbOptions {
  std::string root_name = "tree";
  std::string scene_name = "forest";
  nlohmann::json root_extras;   // null: none
  bool flatten_leaves = false;  // leaves as one mesh with COLOR_0, not EXT_mesh_gpu_instancing
  bool forest_extras = true;    // extras.forest (meta + bake data)
};
std::vector<uint8_t> encode_glb(const TreeModel& model, const GlbOptions& options = {});
// Writes to a temporary file beside `path`, then renames: never leaves a partial file.
void save_glb(const TreeModel& model, const std::filesystem::path& path);
// Missing, truncated or malformed file -> InputError naming the file.
TreeModel decode_glb(std::span<const uint8_t> bytes, const std::string& name);
TreeModel load_glb(const std::filesystem::path& path);

// Writes bytes to `path` atomically (temp file + rename); throws InputError on failure.
void write_file_atomic(const std::filesystem::path& path, std::span<const uint8_t> bytes);

}  // namespace forest
