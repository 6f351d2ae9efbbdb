// A meshed tree: what an asset (.glb) stores and what the engine uploads.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "generators/asset/bake_data.h"
#include "generators/tree/tree_graph.h"

namespace forest {

struct Vertex {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 1.0f, 0.0f};
  glm::vec2 uv{0.0f};
};

struct Mesh {
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;  // triangle list, counter-clockwise seen from outside
};

// A simplified branch mesh and its geometric error: the largest distance (model-space
// meters) between it and LOD0, as reported by meshopt_simplify.
struct MeshLod {
  Mesh mesh;
  float error = 0.0f;
};

// 8-bit RGBA image, row-major, top row first (the leaf texture: alpha is the leaf's mask).
struct Image8 {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> rgba;
};

// A far tree as one textured quad (engine/tools/bake/impostor_bake.h): IMPOSTOR_GRID² views of
// the upper hemisphere (shaders/impostor_math.h), IMPOSTOR_VIEW_SIZE² pixels each, in two
// atlases of IMPOSTOR_ATLAS_SIZE², and its quality per PR table size. Empty: none baked.
struct Impostor {
  Image8 albedo;        // sRGB albedo times the leaves' sky visibility; alpha = coverage
  Image8 normal_depth;  // rg = octahedral model-space normal, b = height toward the view, a = 255
  // Q against full detail at the PR tables' sizes pr_size(size0, b), b < PR_SIZES (the bake's
  // views; empty: not measured, never switched to).
  std::vector<float> q;
  float cutoff = 0.5f;  // blended coverage from which a pixel shows the tree, chosen for the best Q
  bool present() const { return !albedo.rgba.empty(); }
};

struct TreeModel {
  Mesh branches;                        // bark tubes, model space (LOD0)
  std::vector<MeshLod> branch_lods;     // LOD1, LOD2, ...: coarser, errors increasing
  Mesh leaf_card;                       // one leaf, local space: blade along +Y, normal +Z
  Image8 leaf_texture;                  // mapped on leaf_card by its uv; empty = untextured
  // Bark (make_bark_textures): sRGB albedo (the whole base colour; empty = untextured, the
  // bark is bark_color) and tangent-space normal map, repeated over the branch meshes' uv.
  Image8 bark_texture;
  Image8 bark_normal;
  float bark_tile_meters = 0.0f;        // metres one texture tile covers (0: not recorded)
  std::vector<LeafPlacement> leaves;    // instances of leaf_card (in priority order once baked)
  Mesh hull;  // metaball hull (bake), empty before bake
  Impostor impostor;  // bake: the far tree's quad, stored as material "impostor"
  BakeData bake;  // hull samples, leaf order name, PR tables (bake); extras.forest at the asset boundary
  glm::vec4 bounding_sphere{0.0f};      // xyz center, w radius: encloses branches and leaves
  glm::vec3 bark_color{0.30f, 0.22f, 0.15f};  // linear RGB
  glm::vec3 leaf_color{0.18f, 0.35f, 0.08f};  // linear RGB
  // extras.forest: method, seed, parameters... (the bake keys of `bake` are added on encode and
  // taken out on decode: they never appear here)
  nlohmann::json meta = nlohmann::json::object();
};

}  // namespace forest
