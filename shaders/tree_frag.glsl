// Bark and leaves (tree.frag; leaf_msaa.frag for leaves with MSAA): two-sided diffuse with leaf
// translucency, fog. Leaves (specialization LEAF) take color and coverage from the model's leaf
// texture, read at a mip level of our own (leaf_lod), alpha-tested at 0.5; with MSAA (LEAF_MSAA)
// the test is made at every sample (leaf_sample_mask); their back faces are the paler
// undersides. Bark takes its colour from the bark albedo array and perturbs its normal by the
// bark normal map, in a tangent frame from screen-space derivatives.
#include "common.glsl"
#include "lighting.glsl"
#include "impostor_math.h"

layout(constant_id = SPEC_LEAF) const bool LEAF = false;
#ifdef LEAF_MSAA
layout(constant_id = SPEC_COVERAGE_SAMPLES) const uint COVERAGE_SAMPLES = 4u;
#endif
layout(constant_id = SPEC_COVERAGE_LATTICES) const bool COVERAGE_LATTICES = false;
layout(constant_id = SPEC_LEAF_SHADOW_PER_FRAGMENT) const bool LEAF_SHADOW_PER_FRAGMENT = false;
// The views other than the shaded picture (FrameData.view_flags: mask, λ, shadow visibility,
// impostor bake) are read only where this is true: the shaded frame's pipelines set it false,
// since lavapipe's fragment shaders pay for both sides of every branch, taken or not (draw_pass.h).
layout(constant_id = SPEC_VIEWS) const bool VIEWS = true;

// A view of FrameData.view_flags, never in the shaded pipelines.
bool view(uint flag) { return VIEWS && (frame.view_flags & flag) != 0; }

layout(set = 0, binding = BINDING_LEAF_TEXTURES) uniform sampler2DArray leaf_textures;
layout(set = 0, binding = BINDING_BARK_ALBEDO) uniform sampler2DArray bark_albedo;
layout(set = 0, binding = BINDING_BARK_NORMALS) uniform sampler2DArray bark_normals;

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec3 in_albedo;
layout(location = 3) in vec2 in_ao_translucency;
layout(location = 4) in vec3 in_uv_layer;
layout(location = 5) in float in_sun_visibility;
layout(location = 6) flat in vec2 in_fade_shadow;  // the mesh's share of an impostor fade; a leaf's shadow map (leaf_sun_shadow)
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

// The leaf texture's mip level by the Vulkan spec's isotropic formula (the longer screen-space
// derivative of uv, in texels), computed here rather than left to the sampler: the PR bake's
// lattices (below) read the texture b levels coarser than this in place of a render 2^b times
// smaller, so the bake and every render use one formula by construction, not a driver's
// approximation that textureQueryLod might not share. The per-sample test (leaf_sample_mask)
// reads the same level.
// Whether uv lies on the leaf card: a leaf is drawn as one triangle around its card quad
// (scene_buffers.cpp, leaf_triangle), and the card is the texture's unit square, so this test
// cuts the triangle back to the quad, at each sample where samples are tested.
bool leaf_inside_card(vec2 uv) { return all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0))); }

float leaf_lod() {
  vec2 size = vec2(textureSize(leaf_textures, 0).xy);
  vec2 dx = dFdx(in_uv_layer.xy) * size, dy = dFdy(in_uv_layer.xy) * size;
  return 0.5 * log2(max(max(dot(dx, dx), dot(dy, dy)), 1e-12));
}

#ifdef LEAF_MSAA
// The alpha test per sample, at the pipeline's standard sample positions (uv carried there by
// its screen-space derivatives), as the leaf's sample mask: edges antialiased at the samples'
// resolution, and the covered fraction of a far, sub-pixel needle is what the alpha test of one
// sample per pixel covers on average, which the mips keep (leaf_textures.cpp). Alpha to coverage
// did neither the same way everywhere: a far needle wall (4 samples, 4 px cards) kept 0.28 of its
// coverage on NVIDIA against 0.38 near, and 0.38 on lavapipe, whose mapping of alpha to samples
// differs (gpu.LeafAppearance.NeedleCoverageAndColorKeptAtDistance). False where no sample is
// covered. Other sample counts than 2, 4 and 8 test the pixel centre for every sample; a device
// without standardSampleLocations places its samples elsewhere, and the mask then tests points
// near, not at, its samples.
const vec2 kSamples2[2] = vec2[2](vec2(0.75, 0.75), vec2(0.25, 0.25));
const vec2 kSamples4[4] = vec2[4](vec2(0.375, 0.125), vec2(0.875, 0.375), vec2(0.125, 0.625), vec2(0.625, 0.875));
const vec2 kSamples8[8] = vec2[8](vec2(0.5625, 0.3125), vec2(0.4375, 0.6875), vec2(0.8125, 0.5625), vec2(0.3125, 0.1875),
                                  vec2(0.1875, 0.8125), vec2(0.0625, 0.4375), vec2(0.6875, 0.9375), vec2(0.9375, 0.0625));
vec2 sample_offset(uint s) {
  vec2 p = COVERAGE_SAMPLES == 2u ? kSamples2[s] : COVERAGE_SAMPLES == 4u ? kSamples4[s]
         : COVERAGE_SAMPLES == 8u ? kSamples8[s] : vec2(0.5);
  return p - 0.5;
}

bool leaf_sample_mask(float lod) {
  vec2 dx = dFdx(in_uv_layer.xy), dy = dFdy(in_uv_layer.xy);
  uint mask = 0u;
  for (uint s = 0u; s < COVERAGE_SAMPLES; ++s) {
    vec2 o = sample_offset(s);
    vec3 uv = vec3(in_uv_layer.xy + dx * o.x + dy * o.y, in_uv_layer.z);
    if (leaf_inside_card(uv.xy) && textureLod(leaf_textures, uv, lod).a >= 0.5) mask |= 1u << s;
  }
  gl_SampleMask[0] = int(mask);
  return mask != 0u;
}
#endif

// Bake coverage at every PR size in one render (gpu_types.h): red = covered at this
// resolution; green, blue and alpha = covered at the sizes prune::lattice_size gives them at
// this pixel's parity, 2^b times coarser, where the texture would be read 2^b times coarser
// too (b mip levels up). Blended by MAX without a depth test, so the attachment holds the
// union of all leaves at every size; branches (another pipeline) write white. The cutoff is
// alpha >= 0.5 as in main().
void lattice_coverage() {
  float lod = leaf_lod();
  if (!leaf_inside_card(in_uv_layer.xy)) discard;
  uint parity = pixel_parity(uint(gl_FragCoord.x), uint(gl_FragCoord.y));
  vec4 covered;
  covered.r = textureLod(leaf_textures, in_uv_layer, lod).a >= 0.5 ? 1.0 : 0.0;
  for (uint c = 1u; c < 4u; ++c)
    covered[c] = textureLod(leaf_textures, in_uv_layer, lod + float(lattice_size(c, parity))).a >= 0.5 ? 1.0 : 0.0;
  if (covered == vec4(0.0)) discard;
  out_color = covered;
}

// Bark in bake coverage: drawn once per PR size b = frame.lod.z, with the branch LOD the cull
// pass picks for a render at that size (FrameData.lod.x scaled by 2^-b), into the channels that
// hold size b at this pixel. A frame draws its bark at the LOD of its size, so the tables must
// see that bark: with LOD0 bark in the bake's masks, opt lost 0.006 in mean Q against Cook
// along bench_grove's fly-in, whose frames draw coarser bark; drawn at LOD0 there too, it
// gained 0.007.
void branch_lattice_coverage() {
  uint b = uint(frame.lod.z + 0.5);
  uint parity = pixel_parity(uint(gl_FragCoord.x), uint(gl_FragCoord.y));
  vec4 covered = vec4(b == 0u ? 1.0 : 0.0, 0.0, 0.0, 0.0);
  for (uint c = 1u; c < 4u; ++c) covered[c] = lattice_size(c, parity) == b ? 1.0 : 0.0;
  if (covered == vec4(0.0)) discard;
  out_color = covered;
}

// Impostor bake renders (impostor_bake.h): the view's unlit albedo (leaves times their sky
// visibility, which no later light knows), or the model-space normal and the height toward the
// view camera (the bake's instance has no rotation and scale 1). The attachment is sRGB: the
// normal and height are written decoded so that the stored bytes are the values themselves.
bool impostor_bake_output(vec3 albedo, vec3 n) {
  if (view(VIEW_IMPOSTOR_ALBEDO)) {
    out_color = vec4(albedo * (LEAF ? in_ao_translucency.x : 1.0), 1.0);
    return true;
  }
  if (view(VIEW_IMPOSTOR_NORMAL)) {
    float view_depth = dot(in_world - frame.camera_pos.xyz, frame.camera_forward.xyz);
    float height = clamp(0.5 + (frame.impostor.x - view_depth) * frame.impostor.y, 0.0, 1.0);
    out_color = vec4(srgb_to_linear(vec3(oct_encode_normal(n), height)), 1.0);
    return true;
  }
  return false;
}

void main() {
  // Cross-fade with the tree's impostor (cull.comp): this mesh keeps the pixels below its fade.
  if (in_fade_shadow.x < 1.0 && dither_threshold(gl_FragCoord.xy) >= in_fade_shadow.x) discard;
  if (COVERAGE_LATTICES) {
    if (LEAF) lattice_coverage();
    else branch_lattice_coverage();
    return;
  }
  vec3 albedo = in_albedo;
  if (LEAF) {
    float lod = leaf_lod();
    vec4 texel = textureLod(leaf_textures, in_uv_layer, lod);
#ifdef LEAF_MSAA
    if (!leaf_sample_mask(lod)) discard;
#else
    if (texel.a < 0.5 || !leaf_inside_card(in_uv_layer.xy)) discard;
#endif
    albedo *= texel.rgb;
  }
  if (view(VIEW_MASK)) {  // coverage for PR measurement
    out_color = vec4(1.0, 1.0, 1.0, 1.0);
    return;
  }
  vec3 n = normalize(in_normal);
  if (!gl_FrontFacing) n = -n;
  const bool lambda_view = view(VIEW_LAMBDA);
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
  // Leaves bring the shadow map's visibility from their vertex shader (leaf_sun_shadow) unless
  // the pipeline reads it per fragment: a specialization, since lavapipe pays for both sides
  // of a branch.
  float sun_visibility = LEAF && !LEAF_SHADOW_PER_FRAGMENT ? in_fade_shadow.y : sun_shadow(in_world, n);
  if (view(VIEW_SHADOW)) {
    out_color = vec4(vec3(sun_visibility), 1.0);
    return;
  }
  // The sun past the crown (baked, leaf.vert) and past everything else (the shadow map).
  vec3 hdr = shade(albedo, n, in_world, in_ao_translucency.x, in_ao_translucency.y, sun_visibility * in_sun_visibility);
  out_color = vec4(tone_map(hdr), 1.0);
}
