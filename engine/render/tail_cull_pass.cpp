#include "engine/render/tail_cull_pass.h"

#include <algorithm>

#include "engine/vk/pipelines.h"
#include "generators/core/limits.h"

namespace forest {

TailCullPass create_tail_cull_pass(vk::Context& ctx, VkPipelineLayout layout, uint32_t instance_count,
                                   uint64_t instance_leaves) {
  TailCullPass p;
  // Full subgroups: the shader ranks its invocations by subgroup and lane (tail_cull.comp);
  // TAIL_GROUP_SIZE is a multiple of every device's largest subgroup (vk::required_features).
  p.pipeline = vk::create_compute_pipeline(ctx, layout, "tail_cull_comp",
                                           VK_PIPELINE_SHADER_STAGE_CREATE_REQUIRE_FULL_SUBGROUPS_BIT);
  // Copied out by Renderer::tail_lists (tests).
  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
  p.jobs = vk::create_buffer(ctx, sizeof(gpu::TailJob) * std::max(instance_count, 1u), storage, vk::MemoryUse::device);
  p.capacity = uint32_t(std::clamp<uint64_t>(instance_leaves, 1, kMaxTailLeaves));
  p.leaves = vk::create_buffer(ctx, sizeof(uint32_t) * p.capacity, storage, vk::MemoryUse::device);
  return p;
}

void destroy_tail_cull_pass(vk::Context& ctx, TailCullPass& p) {
  vkDestroyPipeline(ctx.device, p.pipeline, nullptr);
  vk::destroy_buffer(ctx, p.jobs);
  vk::destroy_buffer(ctx, p.leaves);
  p = {};
}

void write_tail_cull_bindings(DescriptorWrites& w, const TailCullPass& p) {
  w.buffer(BINDING_TAIL_JOBS, p.jobs).buffer(BINDING_TAIL_LEAVES, p.leaves);
}

void record_tail_cull_pass(VkCommandBuffer cmd, const TailCullPass& p, const CullPass& cull) {
  if (cull.instance_count == 0) return;
  vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                     VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                         VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.pipeline);
  vkCmdDispatchIndirect(cmd, cull.counts.buffer, offsetof(gpu::DrawCounts, tail_jobs));
}

}  // namespace forest
