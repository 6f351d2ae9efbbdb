#version 460
#extension GL_GOOGLE_include_directive : require
// Bark and leaves: two-sided diffuse with leaf translucency, fog.
#include "common.glsl"

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec3 in_albedo;
layout(location = 3) in vec2 in_ao_translucency;
layout(location = 0) out vec4 out_color;

void main() {
  vec3 n = normalize(in_normal);
  if (!gl_FrontFacing) n = -n;
  out_color = vec4(shade(in_albedo, n, in_world, in_ao_translucency.x, in_ao_translucency.y), 1.0);
}
