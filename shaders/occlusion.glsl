// Occlusion test of one tree instance against the previous frame's depth pyramid (Neubert 2012
// Neubert 2012 §7.4), included by cull.comp after common.glsl.
//
// Reversed Z (infinite far plane): depth = near / view distance, 1 at the near plane and 0
// infinitely far. A larger depth is nearer, and each pyramid texel keeps the MINIMUM depth of
// the pixels it covers = the farthest surface there. A point is hidden only if it lies
// behind that farthest surface, so a texel never hides what any of its pixels shows.

// Share of a tree's tested samples that may hide behind its own foliage (a hull is not
// convex) while it still counts as fully visible: f = visible / (tested · (1 − allowance)).
#define OCCLUSION_SELF_ALLOWANCE 0.1

layout(set = 0, binding = BINDING_DEPTH_PYRAMID) uniform sampler2D depth_pyramid;  // nearest, no reduction
layout(set = 0, binding = BINDING_HULL_SAMPLES, std430) readonly buffer HullSamples { HullSample hull_samples[]; };
layout(set = 0, binding = BINDING_INSTANCE_STATE, std430) buffer InstanceStates { InstanceState instance_states[]; };

// Visible in the previous frame? Points behind its camera or off its screen count as
// visible (conservative, as Neubert 2012 §7.4 prescribes).
bool previous_frame_sees(vec3 world) {
  vec4 clip = frame.prev_view_proj * vec4(world, 1.0);
  if (clip.w <= frame.prev_camera.w) return true;
  vec3 ndc = clip.xyz / clip.w;
  vec2 uv = ndc.xy * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) return true;
  // Level 0: each texel is the farthest depth of the <= 2x2 (3x3 at its seams) pixels under it.
  float farthest = textureLod(depth_pyramid, uv, 0.0).x;
  return ndc.z >= farthest;
}

// f = visible / tested over the model's samples that faced the previous camera. Back-facing
// samples are skipped [ours]: the crown's own front foliage always hides them, and counting
// them would prune a tree standing alone in the open. Each sample is moved toward the camera
// by the model's margin first, so leaves poking out of the hull do not hide their own hull.
float visible_fraction(Instance inst, Model m) {
  float s = inst.position_scale.w;
  uint tested = 0, visible = 0;
  for (uint j = 0; j < m.sample_count; ++j) {
    HullSample hs = hull_samples[m.sample_offset + j];
    vec3 p = inst.position_scale.xyz + rotate_yaw(hs.position.xyz, inst.yaw_cos_sin) * s;
    vec3 to_camera = frame.prev_camera.xyz - p;
    float dist = length(to_camera);
    if (dot(rotate_yaw(hs.normal.xyz, inst.yaw_cos_sin), to_camera) <= 0.0 || dist < 1e-4) continue;
    ++tested;
    if (previous_frame_sees(p + to_camera * min(m.occlusion_margin * s / dist, 0.5))) ++visible;
  }
  return tested > 0 ? min(float(visible) / (float(tested) * (1.0 - OCCLUSION_SELF_ALLOWANCE)), 1.0) : 1.0;
}

// The bounding sphere lies entirely behind the farthest depth of the pyramid texels under its
// screen rectangle (the test of zeux/niagara's drawcull.comp, on the previous frame). The
// rectangle comes from the 8 corners of the sphere's bounding cube; the level is the one
// where it spans at most 2x2 texels, all four of which are read.
bool sphere_hidden(vec3 center, float radius) {
  float near = frame.prev_camera.w;
  // The projection is linear, so a corner's clip position is the centre's plus ± the
  // matrix's first three columns times the radius: one matrix product for all eight (the
  // tail pass runs this once per leaf).
  vec4 clip_center = frame.prev_view_proj * vec4(center, 1.0);
  float w_center = clip_center.w;  // view distance along the axis
  if (w_center - radius <= near) return false;
  vec4 ax = frame.prev_view_proj[0] * radius, ay = frame.prev_view_proj[1] * radius, az = frame.prev_view_proj[2] * radius;
  vec2 lo = vec2(1.0), hi = vec2(0.0);
  for (int c = 0; c < 8; ++c) {
    vec4 clip = clip_center + ((c & 1) != 0 ? ax : -ax) + ((c & 2) != 0 ? ay : -ay) + ((c & 4) != 0 ? az : -az);
    if (clip.w <= near) return false;
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    lo = min(lo, uv), hi = max(hi, uv);
  }
  if (any(lessThan(lo, vec2(0.0))) || any(greaterThan(hi, vec2(1.0)))) return false;  // partly off screen
  vec2 size0 = frame.pyramid.xy;
  float texels = max((hi.x - lo.x) * size0.x, (hi.y - lo.y) * size0.y);
  int level = clamp(int(ceil(log2(max(texels, 1.0)))), 0, int(frame.pyramid.z) - 1);
  ivec2 size = max(ivec2(size0) >> level, ivec2(1));
  ivec2 a = clamp(ivec2(lo * vec2(size)), ivec2(0), size - 1);
  ivec2 b = clamp(ivec2(hi * vec2(size)), ivec2(0), size - 1);
  float farthest = min(min(texelFetch(depth_pyramid, a, level).x, texelFetch(depth_pyramid, ivec2(b.x, a.y), level).x),
                       min(texelFetch(depth_pyramid, ivec2(a.x, b.y), level).x, texelFetch(depth_pyramid, b, level).x));
  float nearest_depth = near / (w_center - radius);
  return nearest_depth < farthest;
}
