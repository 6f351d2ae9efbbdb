// Crown self-shadowing of the leaves [ours], shared by leaf.vert and the CPU (tests), written
// in the common subset of GLSL and C++ like prune_math.h.
//
// A leaf's depth below the crown's hull along a unit direction ω (model space) is an
// "ambient cube" of six baked values (generators/bake/hull/hull_depth.h): pos = D along +x,
// +y, +z, neg = along −x, −y, −z, D(ω) = Σ_i ω_i² · (ω_i ≥ 0 ? pos_i : neg_i). Light through
// the crown falls as exp(−κ · D) (Beer–Lambert, κ = the model's extinction): toward the sun
// that is the sun's transmittance, averaged over the sky (cosine-weighted about +Y, which the
// instance's yaw does not move) the sky's visibility.
#ifndef FOREST_CROWN_LIGHT_H
#define FOREST_CROWN_LIGHT_H

#ifdef __cplusplus
#include <cmath>
#include <glm/glm.hpp>
namespace forest::crown {
using vec3 = glm::vec3;
using glm::dot;
inline float exp(float x) { return std::exp(x); }
inline float sqrt(float x) { return std::sqrt(x); }
inline float cos(float x) { return std::cos(x); }
inline float sin(float x) { return std::sin(x); }
inline float max(float a, float b) { return a > b ? a : b; }
inline float mix(float a, float b, float t) { return a + (b - a) * t; }
#define CROWN_INLINE inline
#else
#define CROWN_INLINE
#endif

// The bounding-sphere fallback (a model baked before crown depths): κ = this optical depth ÷
// the sphere's radius, so that light from the centre to the sphere's edge keeps exp(−0.5). The
// sphere also encloses the trunk and the air around the crown (its paths are long), and the
// model may be no crown at all, hence a mild value.
#define CROWN_FALLBACK_OPTICAL_DEPTH 0.5f
// Sky directions averaged (cosine-weighted Fibonacci disk lifted onto the hemisphere).
#define CROWN_SKY_DIRECTIONS 12
// Light the leaves scatter among themselves keeps a deep leaf from going black: the ambient
// term is mix(CROWN_SKY_FLOOR, 1, sky visibility).
#define CROWN_SKY_FLOOR 0.3f

// D(ω) from the six depths.
CROWN_INLINE float crown_depth_toward(vec3 pos, vec3 neg, vec3 w) {
  vec3 w2 = w * w;
  return w2.x * (w.x >= 0.0f ? pos.x : neg.x) + w2.y * (w.y >= 0.0f ? pos.y : neg.y) +
         w2.z * (w.z >= 0.0f ? pos.z : neg.z);
}

// exp(−κ · D(l)), l = unit direction toward the sun in model space.
CROWN_INLINE float crown_sun_transmittance(vec3 pos, vec3 neg, float kappa, vec3 l) {
  return exp(-kappa * crown_depth_toward(pos, neg, l));
}

// Direction j of the sky set: a point of the unit disk at radius sqrt((j + ½)/N), golden-angle
// azimuth, lifted to the hemisphere about +Y (so equal weights are cosine weights).
CROWN_INLINE vec3 crown_sky_direction(int j) {
  float r = sqrt((float(j) + 0.5f) / float(CROWN_SKY_DIRECTIONS));
  float a = 2.39996323f * float(j);
  return vec3(r * cos(a), sqrt(max(1.0f - r * r, 0.0f)), r * sin(a));
}

// Cosine-weighted mean of exp(−κ · D(ω)) over the upper hemisphere, in [0, 1].
CROWN_INLINE float crown_sky_visibility(vec3 pos, vec3 neg, float kappa) {
  float sum = 0.0f;
  for (int j = 0; j < CROWN_SKY_DIRECTIONS; ++j) sum += exp(-kappa * crown_depth_toward(pos, neg, crown_sky_direction(j)));
  return sum / float(CROWN_SKY_DIRECTIONS);
}

// The ambient occlusion factor the leaf shader applies: never below CROWN_SKY_FLOOR.
CROWN_INLINE float crown_ambient(float sky_visibility) { return mix(CROWN_SKY_FLOOR, 1.0f, sky_visibility); }

// Fallback depths from the bounding sphere (centre c, radius R): the exit distance of p + t e
// along each axis ±e (0 outside the sphere).
CROWN_INLINE float crown_sphere_exit(vec3 p, vec3 c, float radius, vec3 e) {
  vec3 d = p - c;
  float b = dot(d, e);
  float disc = b * b - (dot(d, d) - radius * radius);
  return max(-b + sqrt(max(disc, 0.0f)), 0.0f);
}
CROWN_INLINE vec3 crown_sphere_pos(vec3 p, vec3 c, float radius) {
  return vec3(crown_sphere_exit(p, c, radius, vec3(1.0f, 0.0f, 0.0f)), crown_sphere_exit(p, c, radius, vec3(0.0f, 1.0f, 0.0f)),
              crown_sphere_exit(p, c, radius, vec3(0.0f, 0.0f, 1.0f)));
}
CROWN_INLINE vec3 crown_sphere_neg(vec3 p, vec3 c, float radius) {
  return vec3(crown_sphere_exit(p, c, radius, vec3(-1.0f, 0.0f, 0.0f)), crown_sphere_exit(p, c, radius, vec3(0.0f, -1.0f, 0.0f)),
              crown_sphere_exit(p, c, radius, vec3(0.0f, 0.0f, -1.0f)));
}

#ifdef __cplusplus
}  // namespace forest::crown
#endif
#undef CROWN_INLINE

#endif
