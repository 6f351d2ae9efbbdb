// Closest point on a triangle mesh through a bounding-volume hierarchy (median splits of
// triangle centroids) searched nearest-box-first, pruning boxes farther than the best hit.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "generators/model/tree_model.h"

namespace forest {

struct MeshNearest {
  struct Node {
    glm::vec3 lo{0.0f}, hi{0.0f};  // bounding box
    uint32_t first = 0, count = 0; // leaf: tris[first .. first + count); inner: count == 0
    uint32_t left = 0, right = 0;  // inner node children
  };
  const Mesh* mesh = nullptr;
  std::vector<Node> nodes;  // nodes[0] is the root
  std::vector<uint32_t> tris;
};

struct NearestHit {
  glm::vec3 point{0.0f};
  glm::vec3 normal{0.0f, 1.0f, 0.0f};  // vertex normals interpolated at the point, unit
  float distance = -1.0f;              // < 0: the mesh has no triangles
  uint32_t triangle = 0;
};

// `mesh` must outlive the result.
MeshNearest make_mesh_nearest(const Mesh& mesh);
NearestHit nearest_on_mesh(const MeshNearest& index, glm::vec3 q);

// Closest point of triangle abc to p (Ericson, Real-Time Collision Detection §5.1.5), with
// its barycentric coordinates.
glm::vec3 closest_on_triangle(glm::vec3 p, glm::vec3 a, glm::vec3 b, glm::vec3 c,
                              glm::vec3* barycentric = nullptr);

}  // namespace forest
