#version 460
#extension GL_GOOGLE_include_directive : require
// Leaf cards in the sun's shadow map: depth only, cut out by the card texture's alpha as the
// camera's leaf pass cuts them (tree.frag), so leaves cast leaf-shaped shadows.
#include "common.glsl"

layout(set = 0, binding = BINDING_LEAF_TEXTURES) uniform sampler2DArray leaf_textures;
layout(location = 4) in vec3 in_uv_layer;

void main() {
  // A leaf is one triangle around its card; the card is the texture's unit square (tree_frag.glsl).
  if (any(lessThan(in_uv_layer.xy, vec2(0.0))) || any(greaterThan(in_uv_layer.xy, vec2(1.0))) ||
      texture(leaf_textures, in_uv_layer).a < 0.5)
    discard;
}
