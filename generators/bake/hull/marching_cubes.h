// Marching cubes (Lorensen & Cline 1987) on a regular grid of samples, written without a case
// table: in every cell the iso-contour is assembled from its six face segments into closed
// polygons. Each face's ambiguous (saddle) case is decided from that face's four samples
// alone (mean value against the iso-value), so the two cells sharing a face always agree and
// the surface is closed (watertight, 2-manifold by construction) wherever the grid's border
// samples lie below the iso-value.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "generators/model/tree_model.h"

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
// from outside (the low-value side). Vertices sit on grid edges and are shared between cells
// (indexed by edge), plus one centre vertex per polygon of five or more sides; normals are
// left at +Y for the caller to set. Deterministic.
// Vertex placement: linear interpolation of the two samples, or, when `field` is given (the
// function the grid samples), a few regula-falsi steps on it along the edge. That matters
// for fields that fall off steeply (metaballs), where linear interpolation can put a vertex
// far outside the true surface; vertices stay on their edges, so topology is unchanged.
Mesh marching_cubes(const ScalarGrid& grid, float iso,
                    const std::function<float(glm::vec3)>& field = {});

}  // namespace forest
