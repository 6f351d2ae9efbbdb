#version 460
#extension GL_GOOGLE_include_directive : require
// Debug overlay: the depth pyramid the occlusion test of this frame reads (the previous
// frame's farthest depth per texel, Neubert 2012 §7.4 [ours]) at one coarse level, in grey:
// white is near, black is far (log distance), the sky black. Shows what the cull pass can hide
// behind: a tree is culled where its samples fall behind this picture.
#include "gpu_types.h"

layout(set = 0, binding = BINDING_FRAME) uniform FrameBlock { FrameData frame; };
layout(set = 0, binding = BINDING_DEPTH_PYRAMID) uniform sampler2D depth_pyramid;  // nearest, no reduction

layout(location = 0) in vec2 in_uv;
layout(location = 0) out vec4 out_color;

void main() {
  // Level 2 (a quarter of level 0's resolution per axis) when there is one: coarse enough to
  // see the reduction, fine enough to read the scene.
  float level = min(2.0, frame.pyramid.z - 1.0);
  float farthest = textureLod(depth_pyramid, in_uv, level).x;
  // Reversed infinite Z: depth = near / distance (near: the pyramid frame's, prev_camera.w).
  // Grey falls with log distance, white at the near plane to black at 2 km; the far plane
  // (sky, depth 0) is black.
  float near = frame.prev_camera.w;
  float dist = farthest > 0.0 ? near / farthest : 1e9;
  float grey = 1.0 - clamp(log2(dist / near) / log2(2000.0 / near), 0.0, 1.0);
  out_color = vec4(vec3(grey), 1.0);
}
