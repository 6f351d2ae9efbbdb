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

vec4 unpack_tint(uint t) { return vec4(unpackUnorm4x8(t)) * (255.0 / 128.0); }

// Sky radiance in direction d (unit, world space).
vec3 sky_color(vec3 d) {
  float up = clamp(d.y, 0.0, 1.0);
  vec3 c = mix(frame.sky_horizon.rgb, frame.sky_zenith.rgb, pow(up, 0.45));
  if (d.y < 0.0) c = frame.sky_horizon.rgb * mix(1.0, 0.6, clamp(-d.y * 4.0, 0.0, 1.0));
  float s = max(dot(d, frame.sun_dir.xyz), 0.0);
  c += vec3(1.0, 0.9, 0.7) * (pow(s, 600.0) * 8.0 + pow(s, 12.0) * 0.12) * frame.sun_dir.w / 3.0;
  return c;
}

// Sun + sky hemisphere lighting of a diffuse surface, then aerial-perspective fog.
// sun_visibility: the fraction of the sun reaching the surface (crown self-shadowing; 1 = all).
vec3 shade(vec3 albedo, vec3 n, vec3 world, float ambient_occlusion, float translucency, float sun_visibility) {
  vec3 l = frame.sun_dir.xyz;
  float sun = (max(dot(n, l), 0.0) + translucency * max(-dot(n, l), 0.0)) * sun_visibility;
  // Hemisphere ambient: sky from above, light bounced off the forest floor from below.
  vec3 sky = mix(vec3(0.20, 0.19, 0.13), mix(frame.sky_horizon.rgb, frame.sky_zenith.rgb, 0.5), n.y * 0.5 + 0.5);
  vec3 lit = albedo * (sun * frame.sun_dir.w * vec3(1.0, 0.95, 0.85) * 0.5 + sky * 0.6 * ambient_occlusion);
  float dist = length(world - frame.camera_pos.xyz);
  float fog = 1.0 - exp(-dist * frame.fog.w);
  return mix(lit, frame.fog.rgb, fog);
}
