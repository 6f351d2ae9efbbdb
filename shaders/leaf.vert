#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_ARB_shader_draw_parameters : require
// Leaves drawn as instances of the model's card: one indirect draw per visible tree drawing
// its leaves [0, k); gl_InstanceIndex (which includes firstInstance) is the leaf. The
// comparison form of leaf_pulled.vert (VIEW_LEAF_INSTANCED); the body is leaf_body.glsl.
#include "leaf_body.glsl"
