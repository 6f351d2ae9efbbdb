#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_ARB_shader_draw_parameters : require
// Leaves in the sun's shadow map, drawn as instances of the card (shadow_pass.h): leaf.vert
// without the light, which leaf_body.glsl computes for the camera only. Above all it does not
// read the shadow map (leaf_sun_shadow), which this pass is drawing.
#define LEAF_CASTER 1
#include "leaf_body.glsl"
