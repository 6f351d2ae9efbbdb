// Medial-axis thinning of a voxel solid: distance-ordered homotopic thinning (Pudney 1998).
// Voxels are visited from the boundary inward in increasing distance to the boundary; a voxel
// is deleted when it is a simple point -- deleting it changes no topology: its foreground
// 26-neighbours form one 26-connected component and the background of its 18-neighbourhood
// one 6-connected component touching it (Bertrand & Malandain 1994) -- and it is not an
// anchor. What remains is the thinnest set with the solid's topology that keeps every anchor:
// curves that join the anchors along the ridges of the distance map (the medial axis), since
// the deepest voxels are the last to be offered for deletion.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace forest {

struct VoxelSolid {
  glm::ivec3 dims{0};
  std::vector<uint8_t> occupied;  // x fastest, then y, then z
  size_t index(glm::ivec3 c) const {
    return (size_t(c.z) * size_t(dims.y) + size_t(c.y)) * size_t(dims.x) + size_t(c.x);
  }
  glm::ivec3 cell(size_t i) const {
    return {int(i % size_t(dims.x)), int((i / size_t(dims.x)) % size_t(dims.y)),
            int(i / (size_t(dims.x) * size_t(dims.y)))};
  }
  bool at(glm::ivec3 c) const {
    return c.x >= 0 && c.y >= 0 && c.z >= 0 && c.x < dims.x && c.y < dims.y && c.z < dims.z &&
           occupied[index(c)];
  }
};

// Distance (in cells, 26-neighbour Euclidean steps) from each occupied voxel to the nearest
// voxel outside the solid; +inf outside.
std::vector<double> boundary_distance(const VoxelSolid& solid);

// Whether deleting voxel c from the solid keeps its topology (26/6 connectivity).
bool is_simple_voxel(const VoxelSolid& solid, glm::ivec3 c);

// Thins `solid` in place; `anchors` (voxel indices) are never deleted. `distance` orders the
// deletions (boundary_distance of the solid before thinning).
void thin_to_anchors(VoxelSolid& solid, const std::vector<size_t>& anchors,
                     const std::vector<double>& distance);

}  // namespace forest
