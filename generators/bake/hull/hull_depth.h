// Crown self-shadowing baked from the metaball hull [ours]: per leaf, how much crown lies
// between it and the outside along each direction, as an "ambient cube" of six depths, and
// per model the extinction κ that turns a depth into a transmittance exp(−κ · depth)
// (shaders/crown_light.h evaluates both at run time, for any sun and instance rotation).
//
// Depth along ω from a point p: the path length inside the hull (F ≥ iso) of the ray
// p + t ω, t ≥ 0, summed over every in-hull segment until the ray leaves the field's grid
// (gaps in the crown let light through). Sampled along kCrownDirections fixed directions (a
// Fibonacci sphere) with a step of `step_fraction` · r on the field sampled at that spacing
// (trilinear), then least-squares fitted by D(ω) = Σ_i ω_i² · D[axis i, sign of ω_i], the
// basis b_k(ω) = max(±ω_i, 0)² (Σ_k b_k = 1, so a constant depth is fitted exactly);
// results are clamped ≥ 0.
//
// κ by Beer–Lambert with a spherical leaf-angle distribution (projection G = 0.5):
// κ = 0.5 · (one-sided leaf area) / (hull volume), leaf area = card area × the card
// texture's coverage (texels with alpha ≥ 0.5, the shader's cutoff) × scale², the volume
// from the closed hull mesh by the divergence theorem; clamped to [kMinCrownExtinction,
// kMaxCrownExtinction] per metre (a leaf area density of 0.2 … 6 m²/m³: sparse to very dense
// crowns; the clamp also guards degenerate hulls).
#pragma once
#include <array>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "generators/bake/hull/hull.h"
#include "generators/bake/hull/hull_field.h"

namespace forest {

inline constexpr int kCrownDirections = 64;
inline constexpr float kMinCrownExtinction = 0.1f;  // 1/m
inline constexpr float kMaxCrownExtinction = 3.0f;  // 1/m

struct CrownDepthParams {
  float step_fraction = 0.25f;        // march step and grid spacing, × r
  unsigned max_cells_per_axis = 320;  // the grid coarsens beyond (wide crowns)
};

// The fixed directions (unit, deterministic): index j of kCrownDirections.
glm::vec3 crown_direction(int j);

// Six depths (metres: +x, −x, +y, −y, +z, −z) per point, index-aligned with `points`, in the
// field `field` with iso-value `iso`. Deterministic (the same input gives the same bits, at
// any thread count). Empty field or no points: all zero.
std::vector<CrownCube> crown_depths(const MetaballField& field, float iso, std::span<const glm::vec3> points,
                                     const CrownDepthParams& params = {});

// Volume enclosed by a closed, outward-oriented triangle mesh (divergence theorem); 0 if empty.
double mesh_volume(const Mesh& mesh);

// κ of the model's foliage in its hull (see above). 0 when there is no hull volume or no leaf.
float crown_extinction(const TreeModel& model, const Mesh& hull);

// model.bake.crown = the depths at every leaf centre (leaf order of model.leaves) in the
// hull's field and κ. Nothing when the hull is empty.
void attach_crown_light(TreeModel& model, const Hull& hull, const CrownDepthParams& params = {});

}  // namespace forest
