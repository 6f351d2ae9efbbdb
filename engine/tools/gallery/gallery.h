// `forest gallery`: every species preset of a folder generated in-process (each with its
// own seed), rendered by the engine from the same three-quarter view, labelled with its name
// and laid out on one contact sheet. By default every cell has the same camera (framing the
// tallest tree) and a 1.8 m human silhouette beside the trunk, so sizes compare at a glance.
#pragma once
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "engine/tools/gallery/contact_sheet.h"

namespace forest {

struct GalleryOptions {
  uint32_t size = 256;      // pixels of each cell's picture (square)
  uint32_t columns = 0;     // 0: about square
  float azimuth_deg = 35.0f;
  float elevation_deg = 12.0f;
  uint32_t samples = 4;
  bool common_scale = true;  // one camera for all cells, with a human figure; false: each tree fills its cell
};

struct GalleryEntry {
  std::string name;         // file stem
  std::string method;
  size_t triangles = 0, leaves = 0;
  double height = 0.0;
};

// The *.toml files of `dir`, sorted by name. InputError when the folder is missing or has
// none.
std::vector<std::filesystem::path> list_species_presets(const std::filesystem::path& dir);

// Generates every preset (bad preset -> InputError before anything is rendered), renders
// each, labels it (name; method, triangles, leaves) and composes the sheet. `progress`
// gets (done, total) over generation and rendering together.
FrameImage render_gallery(vk::Context& ctx, const std::vector<std::filesystem::path>& presets,
                          const GalleryOptions& options, std::vector<GalleryEntry>* entries = nullptr,
                          const std::function<void(size_t, size_t)>& progress = {});

// Height of the label band under each picture for a cell size.
uint32_t gallery_label_band(uint32_t size);

}  // namespace forest
