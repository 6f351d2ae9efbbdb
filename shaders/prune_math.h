// Detail-level arithmetic shared by cull.comp, leaf.vert and the CPU (tests, bake), written
// in the common subset of GLSL and C++ so both sides compute the same numbers.
#ifndef FOREST_PRUNE_MATH_H
#define FOREST_PRUNE_MATH_H

#ifdef __cplusplus
#include <algorithm>
#include <cmath>
#include <cstdint>
namespace forest::prune {
using uint = uint32_t;
inline float clamp(float x, float lo, float hi) { return std::min(std::max(x, lo), hi); }
inline float ceil(float x) { return std::ceil(x); }
inline float min(float a, float b) { return std::min(a, b); }
inline uint min(uint a, uint b) { return std::min(a, b); }
inline float max(float a, float b) { return std::max(a, b); }
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

// Position of d between table samples: integer part = lower sample, fraction = weight.
PRUNE_INLINE float d_table_position(float d) {
  d = clamp(d, 0.0f, 1.0f);
  if (d < 0.1f) return d / 0.01f;
  return min(10.0f + (d - 0.1f) / 0.1f, 19.0f);
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
