// Marching cubes (Lorensen & Cline 1987) on a regular grid of samples, written without a case
// table: in every cell the iso-contour is assembled from its six face segments into closed
// polygons. Each face's ambiguous (saddle) case is decided from that face's four samples
// alone (mean value against the iso-value), so the two cells sharing a face always agree and
// the surface is closed (watertight, 2-manifold by construction) wherever the grid's border
// samples lie below the iso-value.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "generators/tree/tree_model.h"

namespace forest {

// Samples at origin + spacing * (i, j, k), 0 <= i < size.x etc.; x fastest.
struct ScalarGrid {
  glm::ivec3 size{0};
  glm::vec3 origin{0.0f};
  float spacing = 1.0f;
  std::vector<float> values;  // size.x * size.y * size.z

  size_t index(int i, int j, int k) const {
    return (size_t(k) * size_t(size.y) + size_t(j)) * size_t(size.x) + size_t(i);
  }
  float at(int i, int j, int k) const { return values[index(i, j, k)]; }
  glm::vec3 point(int i, int j, int k) const { return origin + spacing * glm::vec3(i, j, k); }
};

// The surface {value == iso}; "inside" is value >= iso. Triangles are counter-clockwise seen
// from outside (the low-value side). Vertices sit on grid edges (linear interpolation) and
// are shared between cells (indexed by edge), plus one centre vertex per polygon of five or
// more sides; normals are left at +Y for the caller to set. Deterministic.
Mesh marching_cubes(const ScalarGrid& grid, float iso);

}  // namespace forest
