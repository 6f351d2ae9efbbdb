#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_ARB_shader_draw_parameters : require
// Leaves by vertex pulling: one indexed draw per visible tree through the shared leaf
// triangle pattern; gl_VertexIndex / 4 is the leaf, % 4 the triangle's corner (leaf_draw.glsl). No vertex
// input. The body is leaf_body.glsl.
#define LEAF_PULLED 1
#include "leaf_body.glsl"
