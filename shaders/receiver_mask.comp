#version 460
#extension GL_GOOGLE_include_directive : require
// Receiver mask (after Bittner et al., "Shadow caster culling for efficient shadow mapping",
// I3D 2011): a caster matters to a cascade only if its shadow can fall on a surface the
// camera sees and that cascade shades. The previous frame's depth pyramid (level 0: the
// farthest depth of each <= 2x2 pixels, reversed Z) gives those surfaces; one thread per
// texel puts its world point into the cascades that shade its view depth under this frame's
// camera (those within ±10 % of it, for a camera that moved) and raises its light-space
// cell's depth to the point's. A sun camera is orthographic, so a caster shades only the
// cells under its own light-space footprint, and only receivers deeper than itself:
// shadow_cull.comp skips a caster with no such cell. Sky pixels (depth 0) shade nothing.
#include "common.glsl"

layout(local_size_x = PYRAMID_GROUP_SIZE, local_size_y = PYRAMID_GROUP_SIZE) in;
layout(set = 0, binding = BINDING_DEPTH_PYRAMID) uniform sampler2D depth_pyramid;
layout(set = 0, binding = BINDING_RECEIVER_MASK, std430) buffer ReceiverMask { uint receiver_mask[]; };

void mark(vec3 p, uint c) {
  vec3 q = (frame.shadow_view_proj[c] * vec4(p, 1.0)).xyz;
  vec2 uv = q.xy * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) return;
  uvec2 cell = uvec2(uv * float(RECEIVER_MASK_CELLS));
  uint depth = floatBitsToUint(max(q.z, 1e-30));  // non-negative floats order as their bits
  atomicMax(receiver_mask[c * RECEIVER_MASK_WORDS + cell.y * RECEIVER_MASK_CELLS + cell.x], depth);
  atomicMax(receiver_mask[c * RECEIVER_MASK_WORDS + RECEIVER_MASK_CELLS * RECEIVER_MASK_CELLS], depth);
}

void main() {
  ivec2 t = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(t, ivec2(frame.pyramid.xy)))) return;
  float depth = texelFetch(depth_pyramid, t, 0).x;
  if (depth <= 0.0) return;
  vec2 ndc = (vec2(t) + 0.5) / frame.pyramid.xy * 2.0 - 1.0;
  vec4 w = frame.prev_inv_view_proj * vec4(ndc, depth, 1.0);
  vec3 p = w.xyz / w.w;
  float view_depth = dot(p - frame.camera_pos.xyz, frame.camera_forward.xyz);
  if (view_depth / 1.1 >= frame.shadow_splits.w) return;
  for (uint c = shadow_cascade(view_depth / 1.1); c <= shadow_cascade(view_depth * 1.1); ++c) mark(p, c);
}
