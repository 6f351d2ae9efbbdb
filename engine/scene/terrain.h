// Heightfield terrain: fractal value noise on a square grid centered at the origin.
#pragma once
#include <vector>

#include "engine/scene/scene_file.h"
#include "generators/model/tree_model.h"

namespace forest {

struct Terrain {
  TerrainDesc desc;
  std::vector<float> heights;  // (resolution+1)^2, row-major in z then x
  float height_at(float x, float z) const;       // bilinear, clamped to the grid
  glm::vec3 normal_at(float x, float z) const;
  Mesh mesh() const;                             // triangles facing +Y, counter-clockwise
};

Terrain make_terrain(const TerrainDesc& desc);

}  // namespace forest
