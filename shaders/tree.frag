#version 460
#extension GL_GOOGLE_include_directive : require
// Bark and leaves: two-sided diffuse with leaf translucency, fog. Leaves (specialization
// LEAF) take color and coverage from the model's leaf texture; with MSAA the coverage goes
// to alpha-to-coverage, sharpened so edges stay crisp at every mip level; their back faces
// are the paler undersides. Bark takes its colour from the bark albedo array and perturbs
// its normal by the bark normal map, in a tangent frame from screen-space derivatives.
#include "common.glsl"
#include "lighting.glsl"
#include "impostor_math.h"

layout(constant_id = SPEC_LEAF) const bool LEAF = false;
layout(constant_id = SPEC_ALPHA_TO_COVERAGE) const bool ALPHA_TO_COVERAGE = false;
layout(constant_id = SPEC_COVERAGE_LATTICES) const bool COVERAGE_LATTICES = false;

layout(set = 0, binding = BINDING_LEAF_TEXTURES) uniform sampler2DArray leaf_textures;
layout(set = 0, binding = BINDING_BARK_ALBEDO) uniform sampler2DArray bark_albedo;
layout(set = 0, binding = BINDING_BARK_NORMALS) uniform sampler2DArray bark_normals;

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec3 in_albedo;
layout(location = 3) in vec2 in_ao_translucency;
layout(location = 4) in vec3 in_uv_layer;
layout(location = 5) in float in_sun_visibility;
layout(location = 6) flat in float in_fade;
layout(location = 0) out vec4 out_color;

// The normal n perturbed by tangent-space normal t (glTF convention: +X along +u, +Y along
// −v, +Z along n). The frame comes from the derivatives of position and uv (C. Schüler,
// "Normal mapping without precomputed tangents", 2013): no tangent attribute, right for
// mirrored or sheared uv. Its vectors are the surface gradients of u and v times the
// determinant of the screen-space basis, which is negative in Vulkan's y-down window space
// (and on back faces), hence the sign.
vec3 perturb_normal(vec3 n, vec3 p, vec2 uv, vec3 t) {
  vec3 dp1 = dFdx(p), dp2 = dFdy(p);
  vec2 duv1 = dFdx(uv), duv2 = dFdy(uv);
  vec3 dp2perp = cross(dp2, n), dp1perp = cross(n, dp1);
  float orientation = dot(n, cross(dp1, dp2)) < 0.0 ? -1.0 : 1.0;
  vec3 du = (dp2perp * duv1.x + dp1perp * duv2.x) * orientation;  // ∝ the surface gradient of u
  vec3 dv = (dp2perp * duv1.y + dp1perp * duv2.y) * orientation;
  float len2 = max(dot(du, du), dot(dv, dv));
  if (!(len2 > 1e-30)) return n;  // no uv change across the pixel: keep the mesh normal
  float s = inversesqrt(len2);
  return normalize(mat3(du * s, -dv * s, n) * t);
}

// Bake coverage at every PR size in one render (gpu_types.h): red = covered at this
// resolution, green = covered at the size of this pixel's lattice, 2^b times coarser, where
// the texture would be read 2^b times coarser too (b mip levels up). Blended by MAX without
// a depth test, so the attachment holds the union of all leaves at every size; branches
// (another pipeline) write white. The cutoff is alpha >= 0.5 as in main(): sharpening by
// fwidth moves no texel across it.
void lattice_coverage() {
  float lod = textureQueryLod(leaf_textures, in_uv_layer.xy).y;
  float covered = texture(leaf_textures, in_uv_layer).a >= 0.5 ? 1.0 : 0.0;
  uint b = lattice_of_pixel(uint(gl_FragCoord.x), uint(gl_FragCoord.y));
  float coarse = b > 0u && textureLod(leaf_textures, in_uv_layer, lod + float(b)).a >= 0.5 ? 1.0 : 0.0;
  if (covered == 0.0 && coarse == 0.0) discard;
  out_color = vec4(covered, coarse, 0.0, 1.0);
}

// Impostor bake renders (impostor_bake.h): the view's unlit albedo (leaves times their sky
// visibility, which no later light knows), or the model-space normal and the height toward the
// view camera (the bake's instance has no rotation and scale 1). The attachment is sRGB: the
// normal and height are written decoded so that the stored bytes are the values themselves.
bool impostor_bake_output(vec3 albedo, vec3 n) {
  if ((frame.view_flags & VIEW_IMPOSTOR_ALBEDO) != 0) {
    out_color = vec4(albedo * (LEAF ? in_ao_translucency.x : 1.0), 1.0);
    return true;
  }
  if ((frame.view_flags & VIEW_IMPOSTOR_NORMAL) != 0) {
    float view_depth = dot(in_world - frame.camera_pos.xyz, frame.camera_forward.xyz);
    float height = clamp(0.5 + (frame.impostor.x - view_depth) * frame.impostor.y, 0.0, 1.0);
    out_color = vec4(srgb_to_linear(vec3(oct_encode_normal(n), height)), 1.0);
    return true;
  }
  return false;
}

void main() {
  // Cross-fade with the tree's impostor (cull.comp): this mesh keeps the pixels below its fade.
  if (in_fade < 1.0 && dither_threshold(gl_FragCoord.xy) >= in_fade) discard;
  if (LEAF && COVERAGE_LATTICES) {
    lattice_coverage();
    return;
  }
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
  const bool lambda_view = (frame.view_flags & VIEW_LAMBDA) != 0;
  if (LEAF && !gl_FrontFacing && !lambda_view) {
    // The underside (abaxial side) of a leaf is paler and less saturated than the upper one:
    // fewer chloroplasts under a looser tissue, often hairs or wax.
    float luma = dot(albedo, vec3(0.2126, 0.7152, 0.0722));
    albedo = mix(albedo, vec3(luma), 0.2) * vec3(1.25, 1.25, 1.1);
  }
  if (!LEAF && !lambda_view) {
    albedo *= texture(bark_albedo, in_uv_layer).rgb;
    n = perturb_normal(n, in_world, in_uv_layer.xy, texture(bark_normals, in_uv_layer).xyz * 2.0 - 1.0);
  }
  if (impostor_bake_output(albedo, n)) return;
  float sun_visibility = sun_shadow(in_world, n);
  if ((frame.view_flags & VIEW_SHADOW) != 0) {
    out_color = vec4(vec3(sun_visibility), clamp(alpha, 0.0, 1.0));
    return;
  }
  // The sun past the crown (baked, leaf.vert) and past everything else (the shadow map).
  vec3 hdr = shade(albedo, n, in_world, in_ao_translucency.x, in_ao_translucency.y, sun_visibility * in_sun_visibility);
  out_color = vec4(tone_map(hdr), clamp(alpha, 0.0, 1.0));
}
