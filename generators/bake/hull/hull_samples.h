// Sample points spread evenly over a surface (Neubert 2012 §7.4: the points whose visibility
// against last frame's depth pyramid gives a tree's occlusion factor f): area-weighted random
// candidates, then farthest-point selection among them.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "generators/model/tree_model.h"

namespace forest {

struct SurfaceSamples {
  std::vector<glm::vec3> points;
  std::vector<glm::vec3> normals;  // interpolated vertex normals, unit
};

// `count` points (fewer only if the mesh is empty); `candidates_per_sample` random
// candidates per requested point feed the farthest-point pass. Deterministic in `seed`.
SurfaceSamples spread_samples(const Mesh& mesh, uint32_t count, uint64_t seed,
                              uint32_t candidates_per_sample = 16);

}  // namespace forest
