#version 460
#extension GL_GOOGLE_include_directive : require
// One thread per tree instance: frustum test of the bounding sphere, branch LOD by projected
// error, then append the compacted indirect draws (branches, and the model's leaves:
// leaf_draw.glsl). With occlusion on, λ is scaled by the tree's visibility in the
// previous frame (occlusion.glsl) and trees hidden there entirely are not drawn; the leaves
// this drops from a partly visible tree become a TailJob for tail_cull.comp, which keeps
// those the previous frame could see. A far tree whose impostor is at least as good as its
// mesh (impostor_switch.glsl) is appended to the impostor list instead, or to both within the
// cross-fade band.
#include "common.glsl"
#include "occlusion.glsl"
#include "tree_detail.glsl"
#include "impostor_switch.glsl"
#include "leaf_draw.glsl"

layout(local_size_x = CULL_GROUP_SIZE) in;
layout(set = 0, binding = BINDING_COMMANDS, std430) writeonly buffer Commands { DrawCommand commands[]; };
layout(set = 0, binding = BINDING_DRAW_COUNTS, std430) buffer Counts { DrawCounts counts; };
layout(set = 0, binding = BINDING_TAIL_JOBS, std430) writeonly buffer TailJobs { TailJob tail_jobs[]; };
layout(set = 0, binding = BINDING_IMPOSTOR_LIST, std430) writeonly buffer Impostors { ImpostorEntry impostors[]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i == 0) {
    counts.tail_groups_y = counts.tail_groups_z = 1;  // tail_cull.comp's dispatch
    for (uint c = 0; c < IMPOSTOR_LISTS; ++c) {  // one quad per tree: the shared quad pattern
      counts.impostor_draws[c].index_count = LEAF_QUAD_INDICES;
      counts.impostor_draws[c].first_index = frame.instance_count > 0 ? models[instances[0].model].leaf_quad_first_index : 0;
    }
  }
  if (i >= frame.instance_count) return;
  if (frame.camera_pos.w > 0.0 && i != uint(frame.camera_pos.w) - 1u) return;  // one tree alone (per-tree PR)
  Instance inst = instances[i];
  Model m = models[inst.model];
  float s = inst.position_scale.w;
  vec3 center = inst.position_scale.xyz + rotate_yaw(m.bounding_sphere.xyz, inst.yaw_cos_sin) * s;
  float radius = m.bounding_sphere.w * s;
  for (int p = 0; p < 6; ++p)
    if (dot(frame.frustum[p].xyz, center) + frame.frustum[p].w < -radius) return;

  // Coarsest level whose error, projected at the sphere's nearest point, stays under the
  // allowed pixels (errors are non-decreasing along the chain).
  float dist = max(distance(center, frame.lod_camera.xyz) - radius, 1e-3);
  uint lod = 0;
  for (uint k = 1; k < m.lod_count; ++k)
    if (m.lod_error[k] * s * frame.lod.x / dist <= frame.lod.y) lod = k;

  // Detail level λ and leaf area scale s from the normalized distance d.
  float lambda, area_scale;
  float lod_distance = distance(center, frame.lod_camera.xyz);
  tree_detail(m, radius, lod_distance, lambda, area_scale);
  uint k = leaf_prefix(lambda, m.leaf_count);
  float shown_lambda = lambda;
  float impostor = impostor_weight(m, lambda, projected_size(radius, lod_distance, frame.lod.x));

  // Occlusion feedback (Neubert 2012 §7.4): λ_occl = λ(d) · o, o = max(f, 0.1) with hysteresis.
  float o = 1.0;
  if ((frame.occlusion & OCCLUSION_ON) != 0) {
    InstanceState st = instance_states[i];
    bool cut = (frame.occlusion & OCCLUSION_CUT) != 0;
    float f = cut ? 1.0 : visible_fraction(inst, m);
    bool hidden = !cut && f == 0.0 && sphere_hidden(center, radius);
    st.occlusion = cut ? 1.0 : occlusion_factor(st.occlusion, f);
    st.visible = f;
    st.occluded = hidden ? 1 : 0;
    instance_states[i] = st;
    if (hidden) {
      atomicAdd(counts.occluded_instances, 1);
      atomicAdd(counts.leaves_saved, k);
      atomicAdd(counts.triangles_saved, k * (m.card_index_count / 3) + m.lod_index_count[lod] / 3);
      return;
    }
    o = st.occlusion;
    shown_lambda = lambda * o;
  }
  if (impostor > 0.0) {
    uint j = atomicAdd(counts.impostor_draws[0].instance_count, 1);
    impostors[j] = ImpostorEntry(i, impostor);
    if (impostor >= 1.0) return;
  }
  if ((frame.occlusion & OCCLUSION_ON) != 0) {
    // [ours] Neubert 2012 §7.4 draws the prefix of λ · o and nothing else, so the leaves of a partly hidden
    // tree that show through gaps in what hides it vanish with the rest. Here the prefix of
    // λ · o is still drawn whole (the floor of Neubert 2012 §7.4 against a wrong estimate), and the rest of
    // the mode's prefix, [λ·o·n, λ·n), is tested leaf by leaf: those the previous frame saw
    // are drawn too. What shows is then the picture of λ itself, so the leaf sizes, area
    // scale and transition band stay those of λ, and only hidden leaves are saved.
    uint k_occl = leaf_prefix(lambda * o, m.leaf_count);
    if (k_occl < k) {
      uint tail = k - k_occl;
      uint base = atomicAdd(counts.tail_leaves, tail);
      bool room = base + tail <= frame.tail_capacity;
      uint j = room ? atomicAdd(counts.tail_jobs, 1) : frame.tail_job_capacity;
      // A job past what one dispatch may run gives its slot back. Only slots at or past the
      // capacity are given back, so no slot below it is ever handed out twice.
      if (room && j >= frame.tail_job_capacity) atomicAdd(counts.tail_jobs, 0xffffffffu);
      if (j < frame.tail_job_capacity) {  // else no room left: the whole prefix is drawn
        uint l = atomicAdd(counts.leaf_draws, 1);
        tail_jobs[j] = TailJob(frame.leaf_command_base + l, m.leaf_offset + k_occl, m.leaf_offset + k, base);
        commands[frame.leaf_command_base + l] = leaf_draw(m, 0, base, i, lambda, area_scale, shown_lambda,
                                                          LEAF_LIST_TAIL, 1.0 - impostor);
        k = k_occl;
      }
    }
  }

  uint b = atomicAdd(counts.branch_draws, 1);
  atomicAdd(counts.lod_draws[lod], 1);
  atomicAdd(counts.branch_triangles, m.lod_index_count[lod] / 3);
  atomicAdd(counts.lambda_sum, uint(clamp(shown_lambda, 0.0, 1.0) * 4096.0 + 0.5));
  commands[b] = DrawCommand(m.lod_index_count[lod], 1, m.lod_first_index[lod], m.lod_vertex_offset[lod], 0, i,
                            lambda, area_scale, shown_lambda, LEAF_LIST_DIRECT, 1.0 - impostor);
  if (k > 0) {
    uint l = atomicAdd(counts.leaf_draws, 1);
    atomicAdd(counts.leaves_drawn, k);
    commands[frame.leaf_command_base + l] = leaf_draw(m, k, m.leaf_offset, i, lambda, area_scale, shown_lambda,
                                                      LEAF_LIST_DIRECT, 1.0 - impostor);
  }
}
