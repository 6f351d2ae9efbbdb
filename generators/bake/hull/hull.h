// Metaball hull of a tree's foliage (Neubert 2012 §7.3.1 "Rendering
// priority"): generators are the leaf-card centres, radius r = 5 % of the plant height, the
// hull is the iso-surface F = a extracted by marching cubes, plus a few sample points on it
// for the run-time occlusion test (Neubert 2012 §7.4).
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "generators/model/tree_model.h"

namespace forest {

struct HullParams {
  float radius_fraction = 0.05f;  // r = radius_fraction * plant height (Neubert 2012 §7.3.1: 5 %)
  // Iso-value a. The thesis writes a = 0 (the union of the balls); a small positive value is
  // our reading (reference note [ours]): it is well defined and only slightly tighter.
  float iso = 0.05f;
  // Grid spacing as a fraction of r. Capped further so that every corner of the cell holding
  // a leaf centre has F >= iso (then every leaf centre is inside the mesh): with a = 0.05
  // any value <= 0.5 keeps that guarantee.
  float cell_fraction = 0.5f;
  uint32_t max_cells_per_axis = 320;  // bounds memory and time; coarsens the grid beyond
  uint32_t sample_count = 64;         // hull sample points for occlusion
  uint64_t seed = 1;                  // sample placement
};

struct Hull {
  Mesh mesh;                               // closed, CCW from outside, normals = -grad F
  std::vector<glm::vec3> samples;          // on the mesh, spread evenly
  std::vector<glm::vec3> sample_normals;   // outward, unit
  float iso = 0.0f;
  float radius = 0.0f;
};

// Centre of the leaf card (blade along local +Y from 0 to scale) and its unit normal (+Z).
glm::vec3 leaf_center(const LeafPlacement& leaf);
glm::vec3 leaf_normal(const LeafPlacement& leaf);

// Height of the plant: top minus bottom over branch vertices and leaf centres (0 if empty).
float plant_height(const TreeModel& model);

// No leaves -> an empty hull (no mesh, no samples). Throws InputError for a plant height
// that is not positive and finite, bad parameters, or a non-finite leaf.
Hull build_hull(const std::vector<LeafPlacement>& leaves, float plant_height,
                const HullParams& params = {});

// model.hull = hull.mesh; model.bake.hull = the samples, their normals, iso and radius.
void attach_hull(TreeModel& model, const Hull& hull);

}  // namespace forest
