#include "engine/render/pr_count_pass.h"

#include <cstring>
#include <vector>

#include "engine/vk/pipelines.h"

namespace forest {

namespace {

constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;

void create_results(vk::Context& ctx, PrCountPass& p, uint32_t results) {
  p.counts = vk::create_buffer(ctx, sizeof(gpu::PrCounts) * results,
                               kStorage | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                               vk::MemoryUse::device);
  p.readback = vk::create_buffer(ctx, sizeof(gpu::PrCounts) * results, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                 vk::MemoryUse::readback);
  p.result_capacity = results;
}

}  // namespace

PrCountPass create_pr_count_pass(vk::Context& ctx, VkPipelineLayout layout, VkExtent2D frame) {
  PrCountPass p;
  p.pipeline = vk::create_compute_pipeline(ctx, layout, "pr_count_comp");
  p.frame_bytes = VkDeviceSize(frame.width) * frame.height * 4;
  p.reference = vk::create_buffer(ctx, p.frame_bytes, kStorage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::device);
  p.test = vk::create_buffer(ctx, p.frame_bytes, kStorage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::device);
  create_results(ctx, p, 1);
  return p;
}

void destroy_pr_count_pass(vk::Context& ctx, PrCountPass& p) {
  vkDestroyPipeline(ctx.device, p.pipeline, nullptr);
  for (vk::Buffer* b : {&p.reference, &p.test, &p.counts, &p.readback}) vk::destroy_buffer(ctx, *b);
  p = {};
}

void write_pr_count_bindings(DescriptorWrites& w, const PrCountPass& p) {
  w.buffer(BINDING_COVERAGE_REFERENCE, p.reference).buffer(BINDING_COVERAGE_TEST, p.test).buffer(BINDING_PR_COUNTS, p.counts);
}

bool reserve_pr_count(vk::Context& ctx, PrCountPass& p, uint32_t reference_frames, uint32_t results) {
  bool replaced = false;
  if (reference_frames > p.reference_capacity) {
    vk::destroy_buffer(ctx, p.reference);
    p.reference = vk::create_buffer(ctx, p.frame_bytes * reference_frames, kStorage | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                    vk::MemoryUse::device);
    p.reference_capacity = reference_frames;
    replaced = true;
  }
  if (results > p.result_capacity) {
    vk::destroy_buffer(ctx, p.counts);
    vk::destroy_buffer(ctx, p.readback);
    create_results(ctx, p, results);
    replaced = true;
  }
  return replaced;
}

void record_pr_count_pass(VkCommandBuffer cmd, const PrCountPass& p, VkPipelineLayout layout,
                          const gpu::PrCountPush& push) {
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.pipeline);
  vkCmdPushConstants(cmd, layout, kPrCountPushRange.stageFlags, 0, sizeof(push), &push);
  const uint32_t per_group = PR_GROUP_SIZE * PR_PIXELS_PER_INVOCATION;
  vkCmdDispatch(cmd, (push.pixel_count + per_group - 1) / per_group, 1, 1);
}

void record_pr_readback(VkCommandBuffer cmd, const PrCountPass& p, uint32_t count) {
  vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  VkBufferCopy copy{0, 0, sizeof(gpu::PrCounts) * count};
  vkCmdCopyBuffer(cmd, p.counts.buffer, p.readback.buffer, 1, &copy);
  vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                     VK_ACCESS_2_HOST_READ_BIT);
}

std::vector<gpu::PrCounts> read_pr_counts(const PrCountPass& p, uint32_t count) {
  std::vector<gpu::PrCounts> out(count);
  std::memcpy(out.data(), p.readback.mapped, sizeof(gpu::PrCounts) * count);
  return out;
}

}  // namespace forest
