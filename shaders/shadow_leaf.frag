#version 460
#extension GL_GOOGLE_include_directive : require
// Leaf cards in the sun's shadow map: depth only, cut out by the card texture's alpha as the
// camera's leaf pass cuts them (tree.frag), so leaves cast leaf-shaped shadows.
#include "common.glsl"

layout(set = 0, binding = BINDING_LEAF_TEXTURES) uniform sampler2DArray leaf_textures;
layout(location = 4) in vec3 in_uv_layer;

void main() {
  if (texture(leaf_textures, in_uv_layer).a < 0.5) discard;
}
