#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "draw_push.glsl"

layout(location = ATTR_POSITION) in vec3 in_position;
layout(location = ATTR_NORMAL) in vec3 in_normal;
layout(location = ATTR_UV) in vec2 in_uv;
layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;

void main() {
  out_world = in_position;
  out_normal = in_normal;
  gl_Position = draw_view_proj() * vec4(in_position, 1.0);
}
