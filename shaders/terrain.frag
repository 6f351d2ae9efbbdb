#version 460
#extension GL_GOOGLE_include_directive : require
// Ground: grass on gentle slopes, soil and rock on steep ones, with a little noise.
#include "common.glsl"

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(location = 0) out vec4 out_color;

float hash2(vec2 p) { return fract(sin(dot(p, vec2(12.9898, 78.233))) * 43758.5453); }

// Smooth value noise: patches of lighter and darker ground without a visible grid.
float value_noise(vec2 p) {
  vec2 i = floor(p), f = fract(p);
  f = f * f * (3.0 - 2.0 * f);
  return mix(mix(hash2(i), hash2(i + vec2(1, 0)), f.x), mix(hash2(i + vec2(0, 1)), hash2(i + vec2(1, 1)), f.x), f.y);
}

void main() {
  vec3 n = normalize(in_normal);
  vec3 grass = vec3(0.10, 0.17, 0.045), soil = vec3(0.17, 0.12, 0.07), rock = vec3(0.22, 0.21, 0.19);
  float slope = 1.0 - n.y;
  vec3 albedo = mix(grass, soil, smoothstep(0.08, 0.2, slope));
  albedo = mix(albedo, rock, smoothstep(0.25, 0.4, slope));
  float patches = 0.6 * value_noise(in_world.xz * 0.08) + 0.4 * value_noise(in_world.xz * 0.5);
  albedo *= 0.75 + 0.5 * patches;
  albedo = mix(albedo, soil, 0.35 * smoothstep(0.55, 0.8, value_noise(in_world.xz * 0.03 + 17.0)));
  out_color = vec4(shade(albedo, n, in_world, 1.0, 0.0, 1.0), 1.0);
}
