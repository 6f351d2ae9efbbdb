#version 460
#extension GL_GOOGLE_include_directive : require
// Bark and leaves: two-sided diffuse with leaf translucency, fog. Leaves (specialization
// LEAF) take color and coverage from the model's leaf texture; with MSAA the coverage goes
// to alpha-to-coverage, sharpened so edges stay crisp at every mip level.
#include "common.glsl"

layout(constant_id = SPEC_LEAF) const bool LEAF = false;
layout(constant_id = SPEC_ALPHA_TO_COVERAGE) const bool ALPHA_TO_COVERAGE = false;

layout(set = 0, binding = BINDING_LEAF_TEXTURES) uniform sampler2DArray leaf_textures;

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec3 in_albedo;
layout(location = 3) in vec2 in_ao_translucency;
layout(location = 4) in vec3 in_uv_layer;
layout(location = 0) out vec4 out_color;

void main() {
  vec3 albedo = in_albedo;
  float alpha = 1.0;
  if (LEAF) {
    vec4 texel = texture(leaf_textures, in_uv_layer);
    // Sharpen alpha around the 0.5 cutoff by its screen-space rate of change.
    alpha = (texel.a - 0.5) / max(fwidth(texel.a), 1e-4) + 0.5;
    if (!ALPHA_TO_COVERAGE && alpha < 0.5) discard;
    if (ALPHA_TO_COVERAGE && alpha <= 0.0) discard;
    albedo *= texel.rgb;
  }
  if ((frame.view_flags & VIEW_MASK) != 0) {  // coverage for PR measurement
    out_color = vec4(1.0, 1.0, 1.0, clamp(alpha, 0.0, 1.0));
    return;
  }
  vec3 n = normalize(in_normal);
  if (!gl_FrontFacing) n = -n;
  out_color = vec4(shade(albedo, n, in_world, in_ao_translucency.x, in_ao_translucency.y), clamp(alpha, 0.0, 1.0));
}
