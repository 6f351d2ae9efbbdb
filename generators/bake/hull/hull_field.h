// The metaball density of Neubert 2012 §7.3.1: F(q) = sum_i (1 - |q - p_i|^2 / r^2)^2 over the
// generators p_i closer than r, 0 beyond. Generators are bucketed in a grid of cell r, so a
// query touches only the 27 cells around q: O(local) instead of O(generators).
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "generators/bake/hull/marching_cubes.h"

namespace forest {

struct MetaballField {
  std::vector<glm::vec3> centers;  // generators p_i
  float radius = 0.0f;             // influence radius r (one for all generators)
  // Bucket grid over the generators (cell >= radius, so the 27 cells around a query cover
  // its ball): cell c holds order[cell_start[c] .. cell_start[c + 1]).
  glm::vec3 origin{0.0f};
  float cell = 0.0f;
  glm::ivec3 cells{0};
  std::vector<uint32_t> cell_start;
  std::vector<uint32_t> order;
};

// Throws InputError for an empty or non-finite radius or a non-finite centre.
MetaballField make_metaball_field(std::vector<glm::vec3> centers, float radius);

// One generator's contribution D(q) at squared distance d2 (0 outside the radius).
inline float metaball_kernel(float d2, float r2) {
  if (d2 >= r2) return 0.0f;
  float t = 1.0f - d2 / r2;
  return t * t;
}

float field_value(const MetaballField& field, glm::vec3 q);
// dF/dq (points toward higher density, i.e. into the hull).
glm::vec3 field_gradient(const MetaballField& field, glm::vec3 q);
// F at every generator (F(p_i) >= 1: its own contribution is 1). Index-aligned with centers.
std::vector<float> field_at_centers(const MetaballField& field);

// F sampled on a grid of spacing `spacing` covering every generator's ball plus a margin of
// one cell of zeros, so the iso-surface of any positive iso-value is closed. Computed by
// scattering each generator onto the grid points within its radius: O(generators x local).
ScalarGrid sample_field(const MetaballField& field, float spacing);

}  // namespace forest
