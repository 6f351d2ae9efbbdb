#version 460
#extension GL_GOOGLE_include_directive : require
// Precision/Recall pixel counts (Neubert 2012 §7.2.2): reference coverage (full detail) vs test
// coverage (pruned), both RGBA8 frames copied into buffers; covered = channel > 127. Frames
// of the bake's lattice pipeline (push.lattices) are counted per PR size: size 0 from the red
// channel of every pixel, size b >= 1 from the channels prune::lattice_size gives it.
#include "gpu_types.h"
#include "prune_math.h"

layout(local_size_x = PR_GROUP_SIZE) in;
layout(set = 0, binding = BINDING_COVERAGE_REFERENCE, std430) readonly buffer Reference { uint reference[]; };
layout(set = 0, binding = BINDING_COVERAGE_TEST, std430) readonly buffer Test { uint test[]; };
layout(set = 0, binding = BINDING_PR_COUNTS, std430) buffer Counts { PrCounts pr[]; };
layout(push_constant) uniform Push { PrCountPush push; };

shared uint group_tp[PR_SIZES], group_fp[PR_SIZES], group_fn[PR_SIZES];
// Per sub-pixel phase (push.phase_result): the group's counts first, tp and fp packed in 16
// bits each (a group counts 2048 pixels), then added to the global bins once per group: sizes
// 1 and 2 have 2 and 8 counted phases, and global atomics per pixel would put every pixel of
// the render on those few counters (contention on a parallel GPU; on lavapipe the bake time
// did not move either way).
shared uint phase_tp_fp[PR_PHASE_BINS], phase_fn[PR_PHASE_BINS];
const uint PHASE_FP = 1u << 16;

bool covered(uint rgba, uint channel) { return ((rgba >> (8u * channel)) & 0xffu) > 127u; }

// Each invocation counts PR_PIXELS_PER_INVOCATION consecutive pixels in registers and adds
// its totals to the group's once: shared atomics per pixel cost more than the comparison.
void main() {
  const bool phases = push.phase_result != PR_NO_MASK;  // uniform: barriers below are fine
  if (gl_LocalInvocationIndex < PR_SIZES) {
    group_tp[gl_LocalInvocationIndex] = 0;
    group_fp[gl_LocalInvocationIndex] = 0;
    group_fn[gl_LocalInvocationIndex] = 0;
  }
  if (phases)
    for (uint k = gl_LocalInvocationIndex; k < PR_PHASE_BINS; k += PR_GROUP_SIZE) phase_tp_fp[k] = phase_fn[k] = 0u;
  barrier();
  uint tp[PR_SIZES], fp[PR_SIZES], fn[PR_SIZES];
  for (uint s = 0; s < PR_SIZES; ++s) tp[s] = fp[s] = fn[s] = 0u;
  uint first = gl_GlobalInvocationID.x * PR_PIXELS_PER_INVOCATION;
  uint last = min(first + PR_PIXELS_PER_INVOCATION, push.pixel_count);
  uint width = max(push.width, 1u);
  uint x = first % width, y = first / width;
  for (uint i = first; i < last; ++i) {
    uint ref = reference[push.reference_offset + i], tst = test[i];
    uint branch = push.branch_offset != PR_NO_MASK ? reference[push.branch_offset + i] : 0u;
    bool relevant = covered(ref, 0u), retrieved = covered(tst, 0u) || covered(branch, 0u);
    tp[0] += relevant && retrieved ? 1u : 0u;
    fp[0] += !relevant && retrieved ? 1u : 0u;
    fn[0] += relevant && !retrieved ? 1u : 0u;
    if (push.lattices != 0u) {
      uint parity = pixel_parity(x, y);
      for (uint c = 1u; c < 4u; ++c) {
        uint b = lattice_size(c, parity);
        relevant = covered(ref, c);
        retrieved = covered(tst, c) || covered(branch, c);
        tp[b] += relevant && retrieved ? 1u : 0u;
        fp[b] += !relevant && retrieved ? 1u : 0u;
        fn[b] += relevant && !retrieved ? 1u : 0u;
        if (phases && (relevant || retrieved)) {
          uint k = phase_bin(b, x, y);
          if (relevant && !retrieved) atomicAdd(phase_fn[k], 1u);
          else atomicAdd(phase_tp_fp[k], relevant ? 1u : PHASE_FP);
        }
      }
    }
    if (++x == width) x = 0u, ++y;
  }
  for (uint s = 0; s < PR_SIZES; ++s) {
    if (tp[s] != 0u) atomicAdd(group_tp[s], tp[s]);
    if (fp[s] != 0u) atomicAdd(group_fp[s], fp[s]);
    if (fn[s] != 0u) atomicAdd(group_fn[s], fn[s]);
  }
  barrier();
  if (phases)
    for (uint k = gl_LocalInvocationIndex; k < PR_PHASE_BINS; k += PR_GROUP_SIZE) {
      uint tp_fp = phase_tp_fp[k], n = phase_fn[k], at = push.phase_result + k;
      if ((tp_fp & 0xffffu) != 0u) atomicAdd(pr[at].tp, tp_fp & 0xffffu);
      if ((tp_fp >> 16) != 0u) atomicAdd(pr[at].fp, tp_fp >> 16);
      if (n != 0u) atomicAdd(pr[at].fn, n);
    }
  uint sizes = push.lattices != 0u ? PR_SIZES : 1u;
  if (gl_LocalInvocationIndex < sizes) {
    uint s = gl_LocalInvocationIndex, at = push.result + s;
    atomicAdd(pr[at].tp, group_tp[s]);
    atomicAdd(pr[at].fp, group_fp[s]);
    atomicAdd(pr[at].fn, group_fn[s]);
  }
}
