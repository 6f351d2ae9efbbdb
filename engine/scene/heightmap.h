// Heightmap images for terrain: any format OpenImageIO reads (8/16-bit PNG, EXR, TIFF),
// first channel, normalized to [0, 1] (integer formats by their full range).
#pragma once
#include <cstdint>
#include <filesystem>
#include <vector>

namespace forest {

struct Heightmap {
  uint32_t width = 0, height = 0;
  std::vector<float> values;  // row-major, top row first
  // Bilinear at u, v ∈ [0, 1] (0, 0 = centre of the top-left pixel; clamped).
  float sample(float u, float v) const;
};

// InputError naming the file (and `key`) when missing, unreadable, corrupt, too large or
// holding non-finite values.
Heightmap read_heightmap(const std::filesystem::path& file, const char* key = "terrain.heightmap");

}  // namespace forest
