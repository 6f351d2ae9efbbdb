// Poisson-disc node placement by rejection (dart throwing, Xu 2015 Fig. 4.2 steps 1B–1F):
// random points in a box, kept when inside the volume and at least `spacing` from every kept
// point. A uniform grid makes the distance test O(1); a try budget bounds the loop.
#pragma once
#include <cstddef>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "generators/core/rng.h"
#include "generators/methods/common/graph_volume.h"

namespace forest {

using InsideFn = std::function<bool(glm::vec3)>;

// Up to `count` points; fewer when `max_tries` darts are spent first (a full volume).
// Throws InputError (no file) when the grid would be absurdly large (spacing far too small
// for the box).
std::vector<glm::vec3> poisson_disc(const InsideFn& inside, Box box, size_t count, float spacing,
                                    Rng& rng, size_t max_tries);

// Volume of {inside} within box, by 4096 stratified-jitter samples (deterministic given rng).
double estimate_volume(const InsideFn& inside, Box box, Rng& rng);

// The disc spacing at which `count` discs fill `volume` to packing fraction `fill` (π d³/6
// per node): dart throwing reaches fill 0.2 quickly, 0.38 is its jamming limit.
float spacing_for_count(double volume, size_t count, double fill = 0.2);

}  // namespace forest
