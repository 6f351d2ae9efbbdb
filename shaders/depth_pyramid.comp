#version 460
#extension GL_GOOGLE_include_directive : require
// One level of the depth pyramid: each texel = the farthest depth of the source texels it
// covers. Reversed Z (0 = infinitely far), so "farthest" is the MINIMUM.
//
// Level 0 (power of two, at most the depth buffer's size in each axis) reads the depth
// buffer itself: a texel covers 1 to 2 pixels per axis and, with the pixel grid not aligned
// to it, touches up to 3, all of which are read. Levels >= 1 halve exactly: 2x2 texels of
// the level above, read with one bilinear fetch through a MIN-reduction sampler where the
// device has it (samplerFilterMinmax), or as 4 texel fetches (MINMAX_SAMPLER = false).
#include "gpu_types.h"

layout(constant_id = SPEC_MINMAX_SAMPLER) const bool MINMAX_SAMPLER = false;

layout(local_size_x = PYRAMID_GROUP_SIZE, local_size_y = PYRAMID_GROUP_SIZE) in;
layout(set = 0, binding = PYRAMID_BINDING_SOURCE) uniform sampler2D source;  // MIN-reduction sampler iff MINMAX_SAMPLER
layout(set = 0, binding = PYRAMID_BINDING_DESTINATION, r32f) uniform writeonly image2D destination;
layout(push_constant) uniform Level { DepthPyramidPush level; };

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 source_size = level.source_size, destination_size = level.destination_size;
  if (any(greaterThanEqual(p, destination_size))) return;
  float farthest = 1.0;
  if (level.first_level != 0) {
    // Source pixels overlapping [p, p + 1) scaled to the source grid.
    ivec2 lo = (p * source_size) / destination_size;
    ivec2 hi = min(((p + 1) * source_size + destination_size - 1) / destination_size, source_size);
    for (int y = lo.y; y < hi.y; ++y)
      for (int x = lo.x; x < hi.x; ++x) farthest = min(farthest, texelFetch(source, ivec2(x, y), 0).x);
  } else if (MINMAX_SAMPLER) {
    // The 2x2 block's shared corner: the bilinear footprint is exactly those four texels
    // (clamped to the edge where the source is a single texel wide).
    farthest = textureLod(source, vec2(p * 2 + 1) / vec2(source_size), 0.0).x;
  } else {
    ivec2 q = p * 2, last = source_size - 1;
    farthest = min(min(texelFetch(source, min(q, last), 0).x, texelFetch(source, min(q + ivec2(1, 0), last), 0).x),
                   min(texelFetch(source, min(q + ivec2(0, 1), last), 0).x, texelFetch(source, min(q + 1, last), 0).x));
  }
  imageStore(destination, p, vec4(farthest));
}
