// Hemi-octahedral impostor geometry shared by the bake (engine/tools/bake/impostor_bake.cpp)
// and impostor.vert / impostor.frag, in the common subset of GLSL and C++ so that both sides
// agree on every view's direction and image axes.
//
// The upper hemisphere of directions toward the viewer is folded onto the square [-1, 1]²
// (an octahedron cut at its equator, rotated 45° so that the equator runs along the square's
// border: every texel of the square is used). The atlas holds IMPOSTOR_GRID² views, view (i, j)
// at the grid vertex e = 2 (i, j) / (IMPOSTOR_GRID − 1) − 1, so that the views on the border
// look from the horizon. A viewer between four grid vertices blends the three of the
// triangle it falls in (Brucks, "Octahedral impostors", 2018; the hemi-octahedral layout of
// Ryan Brucks' Impostor Baker for Unreal Engine).
#ifndef FOREST_IMPOSTOR_MATH_H
#define FOREST_IMPOSTOR_MATH_H

#ifdef __cplusplus
#include <glm/glm.hpp>

#include "gpu_types.h"
namespace forest::impostor {
using glm::abs;
using glm::cross;
using glm::dot;
using glm::length;
using glm::max;
using glm::normalize;
using uint = uint32_t;
using vec2 = glm::vec2;
using vec3 = glm::vec3;
#define IMPOSTOR_INLINE inline
#else
#define IMPOSTOR_INLINE
#endif

// Direction toward the viewer (model space, any length) → [-1, 1]²; below the horizon it is
// taken at the horizon.
IMPOSTOR_INLINE vec2 hemi_oct_encode(vec3 d) {
  d.y = max(d.y, 0.0f);
  float s = max(abs(d.x) + d.y + abs(d.z), 1e-12f);
  float x = d.x / s, z = d.z / s;
  return vec2(x + z, x - z);
}

IMPOSTOR_INLINE vec3 hemi_oct_decode(vec2 e) {
  float x = 0.5f * (e.x + e.y), z = 0.5f * (e.x - e.y);
  return normalize(vec3(x, 1.0f - abs(x) - abs(z), z));
}

// Position of direction d on the view grid, in [0, IMPOSTOR_GRID − 1]².
IMPOSTOR_INLINE vec2 impostor_grid_position(vec3 d) {
  return (hemi_oct_encode(d) * 0.5f + 0.5f) * float(IMPOSTOR_GRID - 1);
}

// Unit direction from the model toward the camera of view (i, j).
IMPOSTOR_INLINE vec3 impostor_view_direction(uint i, uint j) {
  return hemi_oct_decode(vec2(float(i), float(j)) * (2.0f / float(IMPOSTOR_GRID - 1)) - 1.0f);
}

// The image axes of the view toward direction d: right (+x in the image) and up (−y, the
// image's top row first), as camera_matrices' look-at builds them for a camera at d looking
// back at the model.
IMPOSTOR_INLINE vec3 impostor_right(vec3 d) {
  vec3 up = abs(d.y) > 0.999f ? vec3(0.0f, 0.0f, 1.0f) : vec3(0.0f, 1.0f, 0.0f);
  return normalize(cross(-d, up));
}
IMPOSTOR_INLINE vec3 impostor_up(vec3 d) { return cross(impostor_right(d), -d); }

// Octahedral encoding of a unit normal (the whole sphere) into [0, 1]² (Cigolle et al., "A
// survey of efficient representations for independent unit vectors", 2014).
IMPOSTOR_INLINE vec2 oct_encode_normal(vec3 n) {
  float s = max(abs(n.x) + abs(n.y) + abs(n.z), 1e-12f);
  vec2 p = vec2(n.x / s, n.y / s);
  if (n.z < 0.0f) {
    vec2 f = vec2(p.x >= 0.0f ? 1.0f : -1.0f, p.y >= 0.0f ? 1.0f : -1.0f);
    p = vec2((1.0f - abs(p.y)) * f.x, (1.0f - abs(p.x)) * f.y);
  }
  return p * 0.5f + 0.5f;
}
IMPOSTOR_INLINE vec3 oct_decode_normal(vec2 e) {
  vec2 p = e * 2.0f - 1.0f;
  vec3 n = vec3(p.x, p.y, 1.0f - abs(p.x) - abs(p.y));
  if (n.z < 0.0f) {
    float x = (1.0f - abs(n.y)) * (n.x >= 0.0f ? 1.0f : -1.0f);
    float y = (1.0f - abs(n.x)) * (n.y >= 0.0f ? 1.0f : -1.0f);
    n.x = x;
    n.y = y;
  }
  return normalize(n);
}

#ifdef __cplusplus
}  // namespace forest::impostor
#endif
#endif
