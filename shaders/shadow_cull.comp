#version 460
#extension GL_GOOGLE_include_directive : require
// Shadow casters: one thread per tree instance, for every cascade of the sun's shadow map
// whose caster volume the tree's sphere touches, append the tree's indirect draws (bark and
// leaf prefix) to that cascade's command range. λ and s are those of the camera's mode
// (tree_detail.glsl), so a pruned tree casts its pruned shadow; occlusion plays no part (a
// tree hidden from the camera still casts), nor does the camera frustum (a tree behind the
// camera still shades what it sees). A cascade sees a tree no sharper than its filtered
// texels allow: λ and s are the mode's at the distance where the camera would see the tree at
// the resolution of the PCF footprint (SHADOW_PCF_TEXELS texels), if that is farther than the
// tree is: detail finer than the filter is averaged away, and coarse samples need fewer,
// larger leaves for the same coverage, as a far camera does (Neubert 2012 ch7).
// Branch LOD: the coarsest level whose error stays under that footprint too. A tree casts its
// impostor's shadow (the quad facing the sun) where the camera sees its impostor (more than
// half of it), or where the impostor is at least as good as the mesh at the size the cascade
// sees the tree with: the size at that same distance (impostor_switch.glsl), so far cascades,
// whose texels are metres wide, take impostors long before the camera does.
// With a receiver mask (receiver_mask.comp) a cascade also skips a tree whose light-space
// footprint covers no cell in which the previous frame saw a surface that cascade shades: its
// shadow would fall only where nobody looks (behind a hill, inside a stand the view does not
// reach, past the last visible ground).
#include "common.glsl"
#include "tree_detail.glsl"
#include "impostor_switch.glsl"
#include "leaf_draw.glsl"

layout(local_size_x = CULL_GROUP_SIZE) in;
layout(set = 0, binding = BINDING_COMMANDS, std430) writeonly buffer Commands { DrawCommand commands[]; };
layout(set = 0, binding = BINDING_DRAW_COUNTS, std430) buffer Counts { DrawCounts counts; };
layout(set = 0, binding = BINDING_IMPOSTOR_LIST, std430) writeonly buffer Impostors { ImpostorEntry impostors[]; };
layout(set = 0, binding = BINDING_RECEIVER_MASK, std430) readonly buffer ReceiverMask { uint receiver_mask[]; };

// Does any cell under the sphere's footprint in cascade c's map, grown by one cell (the PCF
// taps, the receivers' normal offset, a camera that moved since the mask was made), hold a
// visible receiver deeper from the sun than the sphere's nearest point? A footprint of more
// than kMaxCells cells asks the cascade's deepest receiver alone.
bool shades_a_receiver(uint c, vec3 center, float radius) {
  const int kMaxCells = 256;
  if (frame.receiver_mask == 0u) return true;
  mat4 m = frame.shadow_view_proj[c];
  vec3 q = (m * vec4(center, 1.0)).xyz;
  uint nearest = floatBitsToUint(max(q.z - radius * length(vec3(m[0].z, m[1].z, m[2].z)), 0.0));
  const uint base = c * RECEIVER_MASK_WORDS;
  if (receiver_mask[base + RECEIVER_MASK_CELLS * RECEIVER_MASK_CELLS] <= nearest) return false;
  vec2 uv = q.xy * 0.5 + 0.5;
  float r = radius / (frame.shadow_texel[c] * frame.shadow_texel.w);  // the map spans texel · resolution metres
  ivec2 lo = max(ivec2(floor((uv - r) * float(RECEIVER_MASK_CELLS))) - 1, ivec2(0));
  ivec2 hi = min(ivec2(floor((uv + r) * float(RECEIVER_MASK_CELLS))) + 1, ivec2(RECEIVER_MASK_CELLS - 1));
  if ((hi.x - lo.x + 1) * (hi.y - lo.y + 1) > kMaxCells) return true;
  for (int y = lo.y; y <= hi.y; ++y)
    for (int x = lo.x; x <= hi.x; ++x)
      if (receiver_mask[base + uint(y * RECEIVER_MASK_CELLS + x)] > nearest) return true;
  return false;
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= frame.instance_count) return;
  Instance inst = instances[i];
  Model m = models[inst.model];
  float s = inst.position_scale.w;
  vec3 center = inst.position_scale.xyz + rotate_yaw(m.bounding_sphere.xyz, inst.yaw_cos_sin) * s;
  float radius = m.bounding_sphere.w * s;
  float camera_distance = distance(center, frame.lod_camera.xyz);
  float camera_lambda, camera_scale;
  tree_detail(m, radius, camera_distance, camera_lambda, camera_scale);
  bool impostor = impostor_weight(m, camera_lambda, projected_size(radius, camera_distance, frame.lod.x)) >= 0.5;
  for (uint c = 0; c < SHADOW_CASCADES; ++c) {
    bool inside = true;
    for (uint p = 0; p < 6; ++p)
      if (dot(frame.shadow_planes[c * 6 + p].xyz, center) + frame.shadow_planes[c * 6 + p].w < -radius) inside = false;
    if (!inside || !shades_a_receiver(c, center, radius)) continue;
    // frame.lod.x: pixels per metre at distance 1, so t metres are one pixel at t · lod.x.
    float cascade_distance = max(camera_distance, SHADOW_PCF_TEXELS * frame.shadow_texel[c] * frame.lod.x);
    float lambda, area_scale;
    tree_detail(m, radius, cascade_distance, lambda, area_scale);
    if (impostor || impostor_weight(m, lambda, projected_size(radius, cascade_distance, frame.lod.x)) >= 0.5) {
      uint j = atomicAdd(counts.impostor_draws[1 + c].instance_count, 1);
      impostors[(1 + c) * frame.instance_count + j] = ImpostorEntry(i, 1.0);
      atomicAdd(counts.shadow_triangles[c], 2);  // its quad
      continue;
    }
    uint k = leaf_prefix(lambda, m.leaf_count);
    uint lod = 0;
    for (uint e = 1; e < m.lod_count; ++e)
      if (m.lod_error[e] * s <= SHADOW_PCF_TEXELS * frame.shadow_texel[c]) lod = e;
    uint base = shadow_command_base(c);
    uint b = atomicAdd(counts.shadow_branch_draws[c], 1);
    atomicAdd(counts.shadow_triangles[c], m.lod_index_count[lod] / 3 + k * (m.card_index_count / 3));
    commands[base + b] = DrawCommand(m.lod_index_count[lod], 1, m.lod_first_index[lod], m.lod_vertex_offset[lod], 0, i,
                                     lambda, area_scale, lambda, LEAF_LIST_DIRECT, 1.0);
    if (k > 0) {
      uint l = atomicAdd(counts.shadow_leaf_draws[c], 1);
      atomicAdd(counts.shadow_leaves[c], k);
      commands[base + frame.instance_count + l] = leaf_draw(m, k, m.leaf_offset, i, lambda, area_scale, lambda,
                                                            LEAF_LIST_DIRECT, 1.0);
    }
  }
}
