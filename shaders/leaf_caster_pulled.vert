#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_ARB_shader_draw_parameters : require
// Leaves in the sun's shadow map by vertex pulling (leaf_pulled.vert; leaf_card.geom makes the
// triangles), without the light and without reading the shadow map being drawn (leaf_caster.vert).
#define LEAF_PULLED 1
#define LEAF_CASTER 1
#include "leaf_body.glsl"
