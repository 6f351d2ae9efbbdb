#version 460
#extension GL_GOOGLE_include_directive : require
// [ours] The leaves occlusion takes from a partly hidden tree, tested one by one (see
// cull.comp): one workgroup per TailJob tests each leaf's bounding sphere against the
// previous frame's depth pyramid and appends those it could see, in priority order, to the
// tail leaf buffer. Their count becomes the leaf count of the job's draw (set_leaf_count).
#include "common.glsl"
#include "occlusion.glsl"
#include "leaf_draw.glsl"

layout(local_size_x = TAIL_GROUP_SIZE) in;
layout(set = 0, binding = BINDING_COMMANDS, std430) buffer Commands { DrawCommand commands[]; };
layout(set = 0, binding = BINDING_DRAW_COUNTS, std430) buffer Counts { DrawCounts counts; };
layout(set = 0, binding = BINDING_TAIL_JOBS, std430) readonly buffer TailJobs { TailJob tail_jobs[]; };
layout(set = 0, binding = BINDING_TAIL_LEAVES, std430) writeonly buffer TailLeaves { uint tail_leaves[]; };

shared uint scan[TAIL_GROUP_SIZE];

void main() {
  TailJob job = tail_jobs[gl_WorkGroupID.x];
  DrawCommand d = commands[job.command];
  Instance inst = instances[d.instance];
  Model m = models[inst.model];
  float s = inst.position_scale.w;
  // A leaf is at most its card's radius, grown by the area scale, from its origin.
  float radius_per_leaf_scale = m.card_radius * sqrt(max(d.area_scale, 0.0)) * s;
  uint t = gl_LocalInvocationID.x;
  uint kept = 0;
  for (uint first = job.first_leaf; first < job.end_leaf; first += TAIL_GROUP_SIZE) {
    uint leaf = first + t;
    uint visible = 0;
    if (leaf < job.end_leaf) {
      Leaf l = leaves[leaf];
      vec3 center = inst.position_scale.xyz + rotate_yaw(l.position_scale.xyz, inst.yaw_cos_sin) * s;
      visible = sphere_hidden(center, l.position_scale.w * radius_per_leaf_scale) ? 0u : 1u;
    }
    // Inclusive prefix sum of `visible` over the group: each kept leaf's place in the list,
    // so the list keeps the priority order (and the frame is the same every run).
    scan[t] = visible;
    barrier();
    for (uint offset = 1; offset < TAIL_GROUP_SIZE; offset <<= 1) {
      uint add = t >= offset ? scan[t - offset] : 0u;
      barrier();
      scan[t] += add;
      barrier();
    }
    if (visible != 0) tail_leaves[job.base + kept + scan[t] - 1] = leaf;
    kept += scan[TAIL_GROUP_SIZE - 1];
    barrier();  // every thread has read scan before the next round writes it
  }
  if (t == 0) {
    set_leaf_count(commands[job.command], kept);
    uint dropped = job.end_leaf - job.first_leaf - kept;
    atomicAdd(counts.leaves_drawn, kept);
    atomicAdd(counts.leaves_saved, dropped);
    atomicAdd(counts.triangles_saved, dropped * (m.card_index_count / 3));
  }
}
