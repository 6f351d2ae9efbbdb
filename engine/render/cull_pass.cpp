#include "engine/render/cull_pass.h"

#include <algorithm>
#include <vector>

#include "engine/vk/pipelines.h"

namespace forest {

CullPass create_cull_pass(vk::Context& ctx, VkPipelineLayout layout, uint32_t instance_count) {
  CullPass p;
  p.pipeline = vk::create_compute_pipeline(ctx, layout, "cull_comp");
  p.instance_count = instance_count;
  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  const uint32_t n = std::max(instance_count, 1u);
  p.commands = vk::create_buffer(ctx, sizeof(gpu::DrawCommand) * COMMANDS_PER_INSTANCE * n,
                                 storage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                 vk::MemoryUse::device);
  p.counts = vk::create_buffer(ctx, sizeof(gpu::DrawCounts),
                               storage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                   VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                               vk::MemoryUse::device);
  // Every instance starts fully visible, so the first frames draw exactly what the mode says.
  std::vector<gpu::InstanceState> states(n, gpu::InstanceState{1.0f, 1.0f, 0u, 0u});
  p.instance_states = vk::create_buffer_from<gpu::InstanceState>(ctx, storage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, states);
  return p;
}

void destroy_cull_pass(vk::Context& ctx, CullPass& p) {
  vkDestroyPipeline(ctx.device, p.pipeline, nullptr);
  for (vk::Buffer* b : {&p.commands, &p.counts, &p.instance_states}) vk::destroy_buffer(ctx, *b);
  p = {};
}

void write_cull_bindings(DescriptorWrites& w, const CullPass& p) {
  w.buffer(BINDING_COMMANDS, p.commands).buffer(BINDING_DRAW_COUNTS, p.counts).buffer(BINDING_INSTANCE_STATE, p.instance_states);
}

void record_cull_pass(VkCommandBuffer cmd, const CullPass& p) {
  vkCmdFillBuffer(cmd, p.counts.buffer, 0, sizeof(gpu::DrawCounts), 0);
  vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  if (p.instance_count == 0) return;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.pipeline);
  vkCmdDispatch(cmd, (p.instance_count + CULL_GROUP_SIZE - 1) / CULL_GROUP_SIZE, 1, 1);
}

}  // namespace forest
