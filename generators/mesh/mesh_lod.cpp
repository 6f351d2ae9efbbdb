#include "generators/mesh/mesh_lod.h"

#include <algorithm>

#include <meshoptimizer.h>

namespace forest {

static_assert(sizeof(Vertex) == 32, "Vertex must be tightly packed for meshoptimizer");

void optimize_mesh(Mesh& mesh) {
  if (mesh.indices.empty() || mesh.vertices.empty()) return;
  std::vector<uint32_t> indices(mesh.indices.size());
  meshopt_optimizeVertexCache(indices.data(), mesh.indices.data(), mesh.indices.size(), mesh.vertices.size());
  std::vector<Vertex> vertices(mesh.vertices.size());
  size_t used = meshopt_optimizeVertexFetch(vertices.data(), indices.data(), indices.size(),
                                            mesh.vertices.data(), mesh.vertices.size(), sizeof(Vertex));
  vertices.resize(used);
  mesh.vertices = std::move(vertices);
  mesh.indices = std::move(indices);
}

std::vector<MeshLod> simplify_lods(const Mesh& lod0, std::span<const float> fractions,
                                   float max_relative_error) {
  std::vector<MeshLod> lods;
  if (lod0.indices.empty()) return lods;
  const float* positions = &lod0.vertices[0].position.x;
  const float scale = meshopt_simplifyScale(positions, lod0.vertices.size(), sizeof(Vertex));
  // Simplify the surface welded by position: the bark's texture seams (a second vertex with
  // u = 1 at u = 0, junction corners using either) would otherwise lock most of the branch
  // mesh. Each position is represented by its first vertex, so a coarse level may show one
  // stretched texture column at a seam; it is seen from afar only.
  std::vector<uint32_t> welded(lod0.indices.size());
  meshopt_generateShadowIndexBuffer(welded.data(), lod0.indices.data(), lod0.indices.size(), positions,
                                    lod0.vertices.size(), sizeof(glm::vec3), sizeof(Vertex));
  const size_t triangles0 = lod0.indices.size() / 3;
  size_t previous = triangles0;
  float error = 0.0f;
  for (float fraction : fractions) {
    size_t target = std::max<size_t>(1, size_t(double(triangles0) * double(fraction))) * 3;
    std::vector<uint32_t> indices(lod0.indices.size());
    float relative = 0.0f;
    size_t count = meshopt_simplify(indices.data(), welded.data(), welded.size(), positions,
                                    lod0.vertices.size(), sizeof(Vertex), target, max_relative_error,
                                    meshopt_SimplifyLockBorder, &relative);
    size_t triangles = count / 3;
    if (triangles == 0 || triangles * 10 > previous * 9) break;
    indices.resize(count);
    MeshLod lod;
    lod.mesh.vertices = lod0.vertices;
    lod.mesh.indices = std::move(indices);
    optimize_mesh(lod.mesh);
    error = std::max(error, relative * scale);
    lod.error = error;
    lods.push_back(std::move(lod));
    previous = triangles;
  }
  return lods;
}

}  // namespace forest
