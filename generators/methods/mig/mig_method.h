// Method `mig` (Xu 2015 ch4, after Xu & Mould 2012): the method with iterated graphs. Level 1:
// Poisson-disc nodes in a union of crown primitives, a Yao-8 graph weighted by edge length,
// b endpoints (in a surface shell of thickness d_e) joined to the root by least-cost paths
// read from ONE Dijkstra run's parent pointers. Level ℓ > 1: around every endpoint e of the
// previous level a subgraph in the part of a sphere (e, r) within angle α of the growth
// vector v_g = (e − R)/|e − R| (optionally rotated about the horizontal, or fixed), k nodes,
// b endpoints joined to e; r shrinks by a per level. No edges between subgraphs. [ours]
// An optional straight trunk (MigParams::trunk_height) is the start of the level-1 paths.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "generators/core/toml_reader.h"
#include "generators/methods/common/graph_volume.h"
#include "generators/species/registry.h"
#include "generators/tree/tree_graph.h"

namespace forest {

struct MigLevel {
  int branching = 6;                    // b: endpoints per (sub)graph
  float alpha = 0.3f * 3.14159265f;     // subgraph cone half-angle α, radians (levels > 1)
  float rotate = 0.0f;                  // rotation of v_g about the horizontal, radians, + = down
  std::optional<glm::vec3> direction;   // fixed v_g (Table 4.1 g: straight down)
  bool around_all = false;              // subgraphs around the endpoints of ALL earlier levels
};

struct MigParams {
  std::vector<Shape> volume;            // level-1 graph volume (union)
  glm::vec3 root{0.0f};                 // R: bottom centre
  size_t nodes = 3000;                  // K: level-1 graph nodes
  float spacing = 0.0f;                 // d; 0 = from K and the volume (fill 0.2)
  float reach = 4.0f;                   // longest Yao edge, in units of d
  float shell = 0.0f;                   // d_e: level-1 endpoint shell thickness (0 = anywhere)
  size_t subgraph_nodes = 150;          // k
  float subgraph_radius = 2.0f;         // r at level 2
  float shrink = 0.7f;                  // a
  // [ours] A straight trunk from R up to R + trunk_height·up (nodes every d) before level 1;
  // 0: none, the level-1 paths start at R (the thesis). Its top is where the level-1 paths
  // leave it (a broadleaf's bole under a decurrent crown), or with trunk_sources_all any of
  // its nodes above R (an excurrent leader with branches along it).
  float trunk_height = 0.0f;
  bool trunk_sources_all = false;
  std::vector<MigLevel> levels;         // levels[0] is level 1
};

struct MigStats {
  size_t graph_nodes = 0;   // nodes in all graphs built
  size_t subgraphs = 0;
  size_t endpoints = 0;     // endpoints joined to the tree
  size_t unreachable = 0;   // endpoint candidates without a path (Yao graphs are directed)
};

// Deterministic for (params, seed). The tree's nodes are in creation order (parent first);
// TreeNode::order = level − 1.
TreeGraph grow_mig(const MigParams& params, uint64_t seed, MigStats* stats = nullptr);

// The method's registry entry (species keys, skeleton pass, built-in preset, inputs).
extern const MethodEntry kMigMethod;

}  // namespace forest
