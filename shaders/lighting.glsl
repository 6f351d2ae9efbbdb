// Light of the fragment shaders, in linear HDR ("scene-linear") units throughout: the sun
// (shadowed by the cascaded shadow map, shadow_pass.h), the sky hemisphere, leaf
// translucency, aerial-perspective fog toward the horizon colour, then one exposure and a
// filmic tone map (ACES) before the sRGB attachment encodes the result. Needs common.glsl.
layout(set = 0, binding = BINDING_SHADOW_MAP) uniform sampler2DArrayShadow shadow_map;

const vec3 kSunColor = vec3(1.0, 0.95, 0.85);

// Sky radiance in direction d (unit, world space).
vec3 sky_color(vec3 d) {
  float up = clamp(d.y, 0.0, 1.0);
  vec3 c = mix(frame.sky_horizon.rgb, frame.sky_zenith.rgb, pow(up, 0.45));
  if (d.y < 0.0) c = frame.sky_horizon.rgb * mix(1.0, 0.6, clamp(-d.y * 4.0, 0.0, 1.0));
  float s = max(dot(d, frame.sun_dir.xyz), 0.0);
  c += kSunColor * (pow(s, 600.0) * 8.0 + pow(s, 12.0) * 0.12) * frame.sun_dir.w / 3.0;
  return c;
}

// One bilinear depth-compare tap. A vertex shader has no implicit level of detail: it reads
// with zero gradients, the same texels of the map's single level.
#ifdef SHADOW_EXPLICIT_LOD
#define SHADOW_TAP(coord) textureGrad(shadow_map, coord, vec2(0.0), vec2(0.0))
#else
#define SHADOW_TAP(coord) texture(shadow_map, coord)
#endif

// Fraction of the sun that reaches world point p (surface normal n, any side): the cascade
// holding p's view depth, a normal offset of 1.5 texels toward the sun against acne, 3×3
// bilinear PCF taps (each a 2×2 compare), faded out over the last 10 % of the distance.
float sun_shadow(vec3 p, vec3 n) {
  if (frame.shadows == 0u) return 1.0;
  float depth = dot(p - frame.camera_pos.xyz, frame.camera_forward.xyz);
  if (depth >= frame.shadow_splits.w) return 1.0;
  uint c = shadow_cascade(depth);
  vec3 toward_sun = dot(n, frame.sun_dir.xyz) >= 0.0 ? n : -n;
  vec4 q = frame.shadow_view_proj[c] * vec4(p + toward_sun * (1.5 * frame.shadow_texel[c]), 1.0);
  vec2 uv = q.xy * 0.5 + 0.5;
  float texel = 1.0 / frame.shadow_texel.w;
  float lit = 0.0;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) lit += SHADOW_TAP(vec4(uv + vec2(x, y) * texel, float(c), q.z));
  return mix(lit / 9.0, 1.0, smoothstep(0.9 * frame.shadow_splits.w, frame.shadow_splits.w, depth));
}

// The shadow map once a leaf, at its card's centre p, in the leaf vertex shader (leaf_body.glsl),
// handed to the fragments with the fade (flat). A leaf is a few centimetres wide, a few texels
// of the nearest cascade at most: only a shadow edge crossing a near leaf is lost, and the leaf
// is lit or shaded whole, as its crown light already is. On lavapipe the 3×3 lookup per
// fragment was a sixth of walk.toml's 4-sample frame, and its fragment shaders run both sides
// of any branch, uniform ones too, so only a shader without it saves it
// (bench/results/leaf_shadow.md). [render] leaf_shadows = "fragment" keeps the lookup per
// fragment (tree_frag.glsl, SPEC_LEAF_SHADOW_PER_FRAGMENT): close-ups, and the comparison.
float leaf_sun_shadow(vec3 p, vec3 n) { return sun_shadow(p, n); }

// A diffuse surface, or a leaf (translucency > 0): n faces the viewer. Sun light through a
// leaf, seen from its unlit side, scatters forward: strongest looking toward the sun
// (a lobe around the light's direction of travel), weak from the side.
// sky_visibility: occlusion of the sky; sun_visibility: sun light reaching the point past its
// own crown (baked) and the shadow map.
vec3 shade(vec3 albedo, vec3 n, vec3 world, float sky_visibility, float translucency, float sun_visibility) {
  vec3 l = frame.sun_dir.xyz;
  vec3 v = normalize(frame.camera_pos.xyz - world);
  float ndl = dot(n, l);
  float forward_lobe = pow(max(-dot(v, l), 0.0), 4.0);
  float through = translucency * max(-ndl, 0.0) * (0.25 + 2.75 * forward_lobe);
  float sun = (max(ndl, 0.0) + through) * sun_visibility;
  // Hemisphere ambient: sky from above, light bounced off the forest floor from below.
  vec3 sky = mix(vec3(0.20, 0.19, 0.13), mix(frame.sky_horizon.rgb, frame.sky_zenith.rgb, 0.5), n.y * 0.5 + 0.5);
  vec3 lit = albedo * (sun * frame.sun_dir.w * kSunColor * 0.5 + sky * 0.6 * sky_visibility);
  float fog = 1.0 - exp(-length(world - frame.camera_pos.xyz) * frame.fog.w);
  return mix(lit, frame.fog.rgb, fog);
}

// Scene-linear → display: exposure, then the ACES filmic curve (Narkowicz, "ACES filmic tone
// mapping curve", 2015); the sRGB attachment applies the transfer function.
vec3 tone_map(vec3 hdr) {
  vec3 x = max(hdr * frame.light.x, 0.0);
  return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}
