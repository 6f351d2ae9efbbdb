#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "lighting.glsl"

layout(location = 0) in vec2 in_ndc;
layout(location = 0) out vec4 out_color;

void main() {
  vec4 p = frame.inv_view_proj * vec4(in_ndc, 0.5, 1.0);
  vec3 d = normalize(p.xyz / p.w - frame.camera_pos.xyz);
  out_color = vec4(tone_map(sky_color(d)), 1.0);
}
