// Batched coverage comparisons for the PR bake (Renderer::set_coverage_views and
// compare_coverage). A bake measures a few hundred (λ, s) points from several views; drawn
// one submit each, every render redraws the branches (identical in all of them) and pays a
// queue round trip. Here the branches are drawn once per view into a mask and each pruned
// render draws only its leaf prefix: in coverage mode every fragment writes the same white,
// so the covered pixels of branches + leaves are exactly the union of the two masks, and
// the counts equal those of render_reference + compare_with_reference (tested).
#include <algorithm>
#include <cstring>

#include "engine/render/renderer.h"

namespace forest {

namespace {

// Coverage jobs run strictly one after another; a full barrier between steps keeps the
// recording simple (lavapipe serializes anyway, and a bake is not a frame).
void full_barrier(VkCommandBuffer cmd) {
  vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
}

void begin(VkCommandBuffer cmd) {
  VK_CHECK(vkResetCommandBuffer(cmd, 0));
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(cmd, &bi));
}

}  // namespace

void Renderer::reserve_coverage(uint32_t reference_frames, uint32_t results) {
  const VkDeviceSize frame_bytes = VkDeviceSize(width_) * height_ * 4;
  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  bool rebind = false;
  if (reference_frames > reference_capacity_) {
    vk::destroy_buffer(ctx_, coverage_reference_);
    coverage_reference_ = vk::create_buffer(ctx_, frame_bytes * reference_frames,
                                            storage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::device);
    reference_capacity_ = reference_frames;
    rebind = true;
  }
  if (results > result_capacity_) {
    vk::destroy_buffer(ctx_, pr_counts_);
    vk::destroy_buffer(ctx_, pr_readback_);
    pr_counts_ = vk::create_buffer(ctx_, sizeof(gpu::PrCounts) * results,
                                   storage | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                   vk::MemoryUse::device);
    pr_readback_ = vk::create_buffer(ctx_, sizeof(gpu::PrCounts) * results, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                     vk::MemoryUse::readback);
    result_capacity_ = results;
    rebind = true;
  }
  if (!rebind) return;
  // Safe to rewrite: every submit of this renderer has been waited for.
  VkDescriptorBufferInfo infos[] = {{coverage_reference_.buffer, 0, VK_WHOLE_SIZE}, {pr_counts_.buffer, 0, VK_WHOLE_SIZE}};
  VkWriteDescriptorSet writes[2];
  const uint32_t bindings[] = {BINDING_COVERAGE_REFERENCE, BINDING_PR_COUNTS};
  for (int i = 0; i < 2; ++i) {
    writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    writes[i].dstSet = set_;
    writes[i].dstBinding = bindings[i];
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[i].pBufferInfo = &infos[i];
  }
  vkUpdateDescriptorSets(ctx_.device, 2, writes, 0, nullptr);
}

void Renderer::record_coverage_pass(VkCommandBuffer cmd, const gpu::FrameData& frame, bool branches, bool leaves) {
  vkCmdUpdateBuffer(cmd, frame_.buffer, 0, sizeof(frame), &frame);
  vkCmdFillBuffer(cmd, counts_.buffer, 0, sizeof(gpu::DrawCounts), 0);
  full_barrier(cmd);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set_, 0, nullptr);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, cull_);
  vkCmdDispatch(cmd, (instance_count_ + CULL_GROUP_SIZE - 1) / CULL_GROUP_SIZE, 1, 1);
  full_barrier(cmd);

  vk::image_barrier(cmd, color_.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                    VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                    VK_ACCESS_2_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  vk::image_barrier(cmd, depth_.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                    VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                    VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
  VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  color.imageView = color_.view;
  color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  depth.imageView = depth_.view;
  depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  depth.clearValue.depthStencil = {0.0f, 0};  // reversed Z
  VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
  ri.renderArea = {{0, 0}, {width_, height_}};
  ri.layerCount = 1;
  ri.colorAttachmentCount = 1;
  ri.pColorAttachments = &color;
  ri.pDepthAttachment = &depth;
  vkCmdBeginRendering(cmd, &ri);
  VkViewport viewport{0.0f, 0.0f, float(width_), float(height_), 0.0f, 1.0f};
  VkRect2D scissor{{0, 0}, {width_, height_}};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 1, &set_, 0, nullptr);
  VkDeviceSize zero = 0;
  vkCmdBindVertexBuffers(cmd, 0, 1, &vertices_.buffer, &zero);
  vkCmdBindIndexBuffer(cmd, indices_.buffer, 0, VK_INDEX_TYPE_UINT32);
  const uint32_t stride = sizeof(gpu::DrawCommand);
  if (branches) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, branches_);
    vkCmdDrawIndexedIndirectCount(cmd, commands_.buffer, 0, counts_.buffer, offsetof(gpu::DrawCounts, branch_draws),
                                  instance_count_, stride);
  }
  if (leaves) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, leaves_pipeline_);
    vkCmdDrawIndexedIndirectCount(cmd, commands_.buffer, VkDeviceSize(instance_count_) * stride, counts_.buffer,
                                  offsetof(gpu::DrawCounts, leaf_draws), instance_count_, stride);
  }
  vkCmdEndRendering(cmd);
  vk::image_barrier(cmd, color_.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                    VK_ACCESS_2_TRANSFER_READ_BIT);
}

void Renderer::set_coverage_views(const std::vector<CameraDesc>& views) {
  if (samples_ != VK_SAMPLE_COUNT_1_BIT || instance_count_ == 0)
    throw vk::VkFailure("coverage batches need a single-sampled renderer with at least one tree");
  const uint32_t count = uint32_t(views.size());
  reserve_coverage(std::max(2 * count, 1u), 1);
  coverage_views_ = views;
  const VkDeviceSize frame_bytes = VkDeviceSize(width_) * height_ * 4;
  begin(cmd_);
  for (uint32_t v = 0; v < count; ++v) {
    FrameSettings full;
    full.mask = true;
    gpu::FrameData fd = frame_data(views[v], full);
    // Slot 2v: full detail (relevant pixels); slot 2v + 1: branches only.
    for (int branches_only = 0; branches_only < 2; ++branches_only) {
      record_coverage_pass(cmd_, fd, true, !branches_only);
      VkBufferImageCopy region{};
      region.bufferOffset = frame_bytes * (2 * v + uint32_t(branches_only));
      region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      region.imageExtent = {width_, height_, 1};
      vkCmdCopyImageToBuffer(cmd_, color_.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, coverage_reference_.buffer, 1,
                             &region);
      full_barrier(cmd_);
    }
  }
  VK_CHECK(vkEndCommandBuffer(cmd_));
  submit_and_wait();
}

std::vector<PrResult> Renderer::compare_coverage(const std::vector<CoverageJob>& jobs) {
  std::vector<PrResult> out(jobs.size());
  if (jobs.empty()) return out;
  for (const CoverageJob& j : jobs)
    if (j.view >= coverage_views_.size()) throw vk::VkFailure("compare_coverage: view without set_coverage_views");
  const uint32_t count = uint32_t(jobs.size());
  reserve_coverage(1, count);
  const uint32_t pixels = width_ * height_;
  begin(cmd_);
  vkCmdFillBuffer(cmd_, pr_counts_.buffer, 0, sizeof(gpu::PrCounts) * count, 0);
  for (uint32_t i = 0; i < count; ++i) {
    const CoverageJob& j = jobs[i];
    FrameSettings test;
    test.mask = true;
    test.prune_mode = PRUNE_FIXED;
    test.fixed_lambda = j.lambda;
    test.fixed_scale = j.scale;
    record_coverage_pass(cmd_, frame_data(coverage_views_[j.view], test), false, true);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {width_, height_, 1};
    vkCmdCopyImageToBuffer(cmd_, color_.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, coverage_test_.buffer, 1, &region);
    full_barrier(cmd_);
    record_pr_count(cmd_, {pixels, 2 * j.view * pixels, (2 * j.view + 1) * pixels, i});
    full_barrier(cmd_);
  }
  VkBufferCopy copy{0, 0, sizeof(gpu::PrCounts) * count};
  vkCmdCopyBuffer(cmd_, pr_counts_.buffer, pr_readback_.buffer, 1, &copy);
  vk::memory_barrier(cmd_, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                     VK_ACCESS_2_HOST_READ_BIT);
  VK_CHECK(vkEndCommandBuffer(cmd_));
  submit_and_wait();
  std::vector<gpu::PrCounts> counts(count);
  std::memcpy(counts.data(), pr_readback_.mapped, sizeof(gpu::PrCounts) * count);
  for (uint32_t i = 0; i < count; ++i) out[i] = {counts[i].tp, counts[i].fp, counts[i].fn};
  return out;
}

}  // namespace forest
