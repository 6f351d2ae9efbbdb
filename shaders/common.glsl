// Bindings and shading shared by every forest shader.
#include "gpu_types.h"
#include "prune_math.h"

layout(set = 0, binding = BINDING_FRAME) uniform FrameBlock { FrameData frame; };
layout(set = 0, binding = BINDING_INSTANCES, std430) readonly buffer Instances { Instance instances[]; };
layout(set = 0, binding = BINDING_MODELS, std430) readonly buffer Models { Model models[]; };
layout(set = 0, binding = BINDING_LEAVES, std430) readonly buffer Leaves { Leaf leaves[]; };
layout(set = 0, binding = BINDING_PRUNE_TABLES, std430) readonly buffer PruneTables { float prune_tables[]; };

// Blue (λ small) -> green -> red (λ = 1), the geometry-level view of Fig 7.15.
vec3 lambda_color(float lambda) {
  return lambda < 0.5 ? mix(vec3(0.05, 0.15, 0.9), vec3(0.1, 0.8, 0.1), lambda * 2.0)
                      : mix(vec3(0.1, 0.8, 0.1), vec3(0.95, 0.1, 0.05), lambda * 2.0 - 1.0);
}

vec3 rotate_yaw(vec3 p, vec2 cs) { return vec3(cs.x * p.x + cs.y * p.z, p.y, -cs.y * p.x + cs.x * p.z); }

vec3 rotate_quat(vec4 q, vec3 v) { return v + 2.0 * cross(q.xyz, cross(q.xyz, v) + q.w * v); }

// The cascade that shades view depth `depth` (< frame.shadow_splits.w): the first whose slice
// reaches past it.
uint shadow_cascade(float depth) {
  return depth < frame.shadow_splits.x ? 0u : depth < frame.shadow_splits.y ? 1u : SHADOW_CASCADES - 1u;
}

// First command of cascade c's draws (gpu_types.h: COMMANDS_PER_INSTANCE).
uint shadow_command_base(uint c) { return frame.instance_count * (3u + 2u * c); }

vec4 unpack_tint(uint t) { return vec4(unpackUnorm4x8(t)) * (255.0 / 128.0); }

// Ordered-dither threshold in (0, 1) of a pixel (4×4 Bayer matrix): a mesh keeps the pixels
// below its fade, its impostor the others, so the two cross-fade without blending.
float dither_threshold(vec2 frag_coord) {
  uvec2 p = uvec2(frag_coord) & 3u;
  const uint bayer[16] = uint[16](0u, 8u, 2u, 10u, 12u, 4u, 14u, 6u, 3u, 11u, 1u, 9u, 15u, 7u, 13u, 5u);
  return (float(bayer[p.y * 4u + p.x]) + 0.5) / 16.0;
}

// sRGB-encoded value → linear: what a shader writes to an sRGB attachment to store `c` itself.
vec3 srgb_to_linear(vec3 c) {
  return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), greaterThan(c, vec3(0.04045)));
}
