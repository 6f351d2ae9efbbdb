#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_ARB_shader_draw_parameters : require
// Leaves by vertex pulling: one indexed draw per visible tree of the shared pattern's points,
// one a leaf; gl_VertexIndex is the leaf (leaf_draw.glsl), and leaf_card.geom makes its
// triangle. No vertex input. The body is leaf_body.glsl.
#define LEAF_PULLED 1
#include "leaf_body.glsl"
