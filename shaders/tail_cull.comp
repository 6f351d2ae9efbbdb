#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
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

// Leaves kept by each subgroup in a round, in two halves used by alternate rounds: a round
// reads its half after the one barrier, and the next round writes the other, so no second
// barrier is needed before the next write.
shared uint subgroup_kept[2][TAIL_GROUP_SIZE];

// Leaves one invocation tests per round, one bit each of its visibility mask.
const uint kLeavesPerInvocation = 32u;

void main() {
  TailJob job = tail_jobs[gl_WorkGroupID.x];
  DrawCommand d = commands[job.command];
  Instance inst = instances[d.instance];
  Model m = models[inst.model];
  float s = inst.position_scale.w;
  // A leaf is at most its card's radius, grown by the area scale, from its origin.
  float radius_per_leaf_scale = m.card_radius * sqrt(max(d.area_scale, 0.0)) * s;
  // This invocation's rank: subgroups in their order, lanes in theirs. The pipeline asks for
  // full subgroups (tail_cull_pass.cpp), so the ranks are exactly 0 … TAIL_GROUP_SIZE − 1.
  uint rank = gl_SubgroupID * gl_SubgroupSize + gl_SubgroupInvocationID;
  uint kept = 0, half_ = 0;
  const uint round_leaves = TAIL_GROUP_SIZE * kLeavesPerInvocation;
  for (uint first = job.first_leaf; first < job.end_leaf; first += round_leaves, half_ ^= 1u) {
    // Each invocation tests a run of consecutive leaves, so the group's barrier and prefix
    // sum come once per TAIL_GROUP_SIZE · 32 leaves: lavapipe spent more on them, once per 64
    // leaves, than on the tests (3.5 M tail leaves of a forest5000 frame: 320 ms of which
    // 70 ms the tests).
    uint run = first + rank * kLeavesPerInvocation;
    uint run_end = min(run + kLeavesPerInvocation, job.end_leaf);
    uint visible = 0;
    for (uint leaf = run; leaf < run_end; ++leaf) {
      Leaf l = leaves[leaf];
      vec3 center = inst.position_scale.xyz + rotate_yaw(l.position_scale.xyz, inst.yaw_cos_sin) * s;
      if (!sphere_hidden(center, l.position_scale.w * radius_per_leaf_scale)) visible |= 1u << (leaf - run);
    }
    // Each kept leaf's place in the list is the count of kept leaves before it, so the list
    // keeps the priority order (and the frame is the same every run): the runs of lower rank
    // in this subgroup by its prefix sum, those of lower subgroups by their totals.
    uint count = uint(bitCount(visible));
    uint before = subgroupExclusiveAdd(count);
    uint total_here = subgroupAdd(count);
    if (subgroupElect()) subgroup_kept[half_][gl_SubgroupID] = total_here;
    barrier();
    uint total = 0;
    for (uint g = 0; g < gl_NumSubgroups; ++g) {
      uint n = subgroup_kept[half_][g];
      before += g < gl_SubgroupID ? n : 0u;
      total += n;
    }
    for (uint slot = job.base + kept + before; visible != 0u; visible &= visible - 1u)
      tail_leaves[slot++] = run + uint(findLSB(visible));
    kept += total;
  }
  if (rank == 0) {
    set_leaf_count(commands[job.command], kept);
    uint dropped = job.end_leaf - job.first_leaf - kept;
    atomicAdd(counts.leaves_drawn, kept);
    atomicAdd(counts.leaves_saved, dropped);
    atomicAdd(counts.triangles_saved, dropped * (m.card_index_count / 3));
  }
}
