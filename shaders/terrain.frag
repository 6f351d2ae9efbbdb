#version 460
#extension GL_GOOGLE_include_directive : require
// Ground: grass on gentle slopes, soil and rock on steep ones, with a little noise.
#include "common.glsl"

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(location = 0) out vec4 out_color;

float noise2(vec2 p) { return fract(sin(dot(floor(p), vec2(12.9898, 78.233))) * 43758.5453); }

void main() {
  vec3 n = normalize(in_normal);
  vec3 grass = vec3(0.10, 0.17, 0.045), soil = vec3(0.17, 0.12, 0.07), rock = vec3(0.22, 0.21, 0.19);
  float slope = 1.0 - n.y;
  vec3 albedo = mix(grass, soil, smoothstep(0.08, 0.2, slope));
  albedo = mix(albedo, rock, smoothstep(0.25, 0.4, slope));
  albedo *= 0.85 + 0.3 * noise2(in_world.xz * 0.7);
  out_color = vec4(shade(albedo, n, in_world, 1.0, 0.0), 1.0);
}
