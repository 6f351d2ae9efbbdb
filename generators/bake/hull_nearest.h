// Closest point on a triangle mesh, accelerated by a uniform grid of triangle bounding boxes
// and a ring-by-ring search that stops once no unvisited cell can hold a closer point.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "generators/tree/tree_model.h"

namespace forest {

struct MeshNearest {
  const Mesh* mesh = nullptr;
  glm::vec3 origin{0.0f};
  float cell = 1.0f;
  glm::ivec3 cells{0};
  std::vector<uint32_t> cell_start;  // triangles of cell c: tris[cell_start[c] .. [c + 1])
  std::vector<uint32_t> tris;
};

struct NearestHit {
  glm::vec3 point{0.0f};
  glm::vec3 normal{0.0f, 1.0f, 0.0f};  // vertex normals interpolated at the point, unit
  float distance = -1.0f;              // < 0: the mesh has no triangles
  uint32_t triangle = 0;
};

// `mesh` must outlive the result. `cell` <= 0 picks about the mean triangle size.
MeshNearest make_mesh_nearest(const Mesh& mesh, float cell = 0.0f);
NearestHit nearest_on_mesh(const MeshNearest& index, glm::vec3 q);

// Closest point of triangle abc to p (Ericson, Real-Time Collision Detection §5.1.5), with
// its barycentric coordinates.
glm::vec3 closest_on_triangle(glm::vec3 p, glm::vec3 a, glm::vec3 b, glm::vec3 c,
                              glm::vec3* barycentric = nullptr);

}  // namespace forest
