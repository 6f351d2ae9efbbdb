// Detail-level arithmetic shared by cull.comp, leaf.vert and the CPU (tests, bake), written
// in the common subset of GLSL and C++ so both sides compute the same numbers.
#ifndef FOREST_PRUNE_MATH_H
#define FOREST_PRUNE_MATH_H

#ifdef __cplusplus
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "gpu_types.h"
namespace forest::prune {
using uint = uint32_t;
inline float clamp(float x, float lo, float hi) { return std::min(std::max(x, lo), hi); }
inline float ceil(float x) { return std::ceil(x); }
inline float min(float a, float b) { return std::min(a, b); }
inline uint min(uint a, uint b) { return std::min(a, b); }
inline float max(float a, float b) { return std::max(a, b); }
inline float sqrt(float x) { return std::sqrt(x); }
inline float log2(float x) { return std::log2(x); }
#define PRUNE_INLINE inline
#else
#define PRUNE_INLINE
#endif

// λ_Cook(d) = (1 − d)², d = normalized distance in [0, 1].
PRUNE_INLINE float lambda_cook(float d) {
  float x = 1.0f - clamp(d, 0.0f, 1.0f);
  return x * x;
}

// Distance of λ_opt table sample i: 10 samples in [0, 0.1), 10 in [0.1, 1].
PRUNE_INLINE float d_sample(uint i) { return i < 10u ? float(i) * 0.01f : 0.1f + float(i - 10u) * 0.1f; }

// The far λ samples of the PR tables, below the first regular one (gpu_types.h): halvings of
// 1 / (S_SAMPLES − 1), f = 0 the largest.
PRUNE_INLINE float far_lambda(uint f) { return 1.0f / (float(S_SAMPLES - 1) * float(2u << f)); }

// Position of d between table samples: integer part = lower sample, fraction = weight.
PRUNE_INLINE float d_table_position(float d) {
  d = clamp(d, 0.0f, 1.0f);
  if (d < 0.1f) return d / 0.01f;
  return min(10.0f + (d - 0.1f) / 0.1f, 19.0f);
}

// Projected size of a sphere of radius r whose centre is `dist` from the camera, in pixels
// across: 2·k·tan(asin(r/dist)), k = pixels per metre at distance 1 (FrameData.lod.x). A
// camera inside the sphere sees it fill any frame.
PRUNE_INLINE float projected_size(float radius, float dist, float pixels_per_meter) {
  float under = dist * dist - radius * radius;
  if (under <= 1e-12f * max(dist * dist, 1.0f)) return 1e9f;
  return 2.0f * pixels_per_meter * radius / sqrt(under);
}

// Position of projected size p among a model's table sizes size0 / 2^b: integer part = the
// larger sample, fraction = weight of the next smaller one; clamped to the sampled range.
PRUNE_INLINE float size_table_position(float p, float size0) {
  return clamp(log2(max(size0, 1e-6f) / max(p, 1e-6f)), 0.0f, float(PR_SIZES - 1));
}

// Bake coverage channels (gpu_types.h, SPEC_COVERAGE_LATTICES): the PR size b >= 1 that
// colour channel c (1 green, 2 blue, 3 alpha) holds at a pixel of parity (x + y) & 1. Red holds
// size 0 at every pixel; the 8 px size (5), the noisiest, is in alpha at every pixel; sizes 1
// and 2 at the even pixels, 3 and 4 at the odd ones. Written for PR_SIZES = 6.
PRUNE_INLINE uint lattice_size(uint channel, uint parity) { return channel == 3u ? 5u : channel + 2u * parity; }
PRUNE_INLINE uint pixel_parity(uint x, uint y) { return (x + y) & 1u; }
// The per-phase count bin (gpu_types.h PR_PHASE_BINS) of size b at pixel (x, y) of a bake
// render: that pixel is the sample point of a render 2^b smaller at phase (x, y) mod 2^b.
PRUNE_INLINE uint phase_bin(uint b, uint x, uint y) {
  uint cell = 1u << b;
  return ((1u << (2u * b)) - 1u) / 3u + (y & (cell - 1u)) * cell + (x & (cell - 1u));
}

// Leaves drawn out of n at detail λ: k = ⌈λ·n⌉, at least one while λ > 0.
PRUNE_INLINE uint leaf_prefix(float lambda, uint n) {
  float k = ceil(clamp(lambda, 0.0f, 1.0f) * float(n));
  return min(uint(k), n);
}

// Size factor of the leaf at prefix position i of k: leaves in the last fraction t of the
// prefix grow from 0 to full size, so a changing λ adds and removes leaves without popping.
PRUNE_INLINE float transition_size(float i, float lambda_n, float t) {
  if (t <= 0.0f) return 1.0f;
  float u = (lambda_n - i) / max(t * lambda_n, 1.0f);  // 1 at the band's start, 0 at the end
  return clamp(u, 0.0f, 1.0f);
}

// Occlusion feedback (Neubert 2012 §7.4): λ_occl = λ(d) · max(f, 0.1), f = visible fraction of
// the hull samples, smoothed over frames by a hysteresis. The thesis gives no formula; ours:
// the factor rises at once when f grows by more than a band or reaches 1 (a tree coming into
// view never waits for its leaves), holds inside the band (a sample or two flickering in and
// out does not move λ), and falls geometrically toward its target, keeping OCCLUSION_KEEP of
// the gap per frame, so a tree that gets hidden thins out over a few frames instead of
// popping: from 1 it reaches ≤ 0.15 after 4 frames.
#define OCCLUSION_FLOOR 0.1f
#define OCCLUSION_KEEP 0.4f
#define OCCLUSION_RISE_BAND 0.1f

PRUNE_INLINE float occlusion_factor(float previous, float visible_fraction) {
  float target = clamp(max(visible_fraction, OCCLUSION_FLOOR), 0.0f, 1.0f);
  if (target >= 1.0f || target >= previous + OCCLUSION_RISE_BAND) return target;
  if (target >= previous) return previous;
  float next = target + (previous - target) * OCCLUSION_KEEP;
  return next - target < 0.01f ? target : next;
}

#ifdef __cplusplus
}  // namespace forest::prune
#endif
#endif
