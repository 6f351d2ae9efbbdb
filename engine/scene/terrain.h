// Heightfield terrain: fractal value noise on a square grid centered at the origin.
#pragma once
#include <vector>

#include "engine/scene/scene_file.h"
#include "generators/model/tree_model.h"

namespace forest {

// A square block of at most kTerrainChunkCells × kTerrainChunkCells cells: its triangles are
// one range of Terrain::mesh()'s indices, so that a view draws only the blocks it can see
// (terrain_cull.h).
struct TerrainChunk {
  uint32_t first_index = 0, index_count = 0;
  glm::vec3 min{0.0f}, max{0.0f};  // bounds of its vertices (m)
};
inline constexpr uint32_t kTerrainChunkCells = 32;

struct Terrain {
  TerrainDesc desc;
  std::vector<float> heights;  // (resolution+1)^2, row-major in z then x
  float height_at(float x, float z) const;       // bilinear, clamped to the grid
  glm::vec3 normal_at(float x, float z) const;
  // Triangles facing +Y, counter-clockwise, chunk by chunk in the order of chunks().
  Mesh mesh() const;
  std::vector<TerrainChunk> chunks() const;
};

Terrain make_terrain(const TerrainDesc& desc);

}  // namespace forest
