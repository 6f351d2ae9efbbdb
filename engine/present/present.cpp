#include "engine/present/present.h"

#include <algorithm>
#include <cstring>
#include <iterator>
#include <string>

#include "engine/vk/pipelines.h"
#include "gpu_types.h"

namespace forest {

namespace {

constexpr VkImageSubresourceRange kColorRange{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};

// Largest rectangle of the source's aspect that fits `extent`, centered (letterbox).
VkOffset3D fit_rect(VkExtent2D source, VkExtent2D extent, VkOffset3D* end) {
  double scale = std::min(double(extent.width) / source.width, double(extent.height) / source.height);
  int32_t w = std::max(1, int32_t(source.width * scale + 0.5)), h = std::max(1, int32_t(source.height * scale + 0.5));
  w = std::min(w, int32_t(extent.width));
  h = std::min(h, int32_t(extent.height));
  VkOffset3D begin{(int32_t(extent.width) - w) / 2, (int32_t(extent.height) - h) / 2, 0};
  *end = {begin.x + w, begin.y + h, 1};
  return begin;
}


// The swapchain image is first touched here: the acquire semaphore is waited at these
// stages and the first layout transition waits on them too.
constexpr VkPipelineStageFlags2 kFirstUse = VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;

// Source to TRANSFER_SRC (it stays there: the renderer's next frame starts from UNDEFINED
// with a barrier whose first scope is the transfer stage).
void source_to_transfer_src(VkCommandBuffer cmd, const vk::Image& source, VkImageLayout layout) {
  if (layout == VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL)
    vk::image_barrier(cmd, source.image, VK_IMAGE_ASPECT_COLOR_BIT, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                      VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  else if (layout != VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL)
    throw vk::VkFailure("present: the rendered image is in an unexpected layout");
}

// Blit (scaled, aspect kept) into the middle, bars cleared. Leaves `target` in TRANSFER_DST.
void record_blit(VkCommandBuffer cmd, const vk::Swapchain& sc, VkImage target, const vk::Image& source,
                 VkImageLayout source_layout, VkOffset3D begin, VkOffset3D end, bool linear) {
  vk::image_barrier(cmd, target, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                    VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, kFirstUse, 0, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                    VK_ACCESS_2_TRANSFER_WRITE_BIT);
  source_to_transfer_src(cmd, source, source_layout);
  bool bars = begin.x > 0 || begin.y > 0 || end.x < int32_t(sc.extent.width) || end.y < int32_t(sc.extent.height);
  if (bars) {
    VkClearColorValue black{{0.0f, 0.0f, 0.0f, 1.0f}};
    vkCmdClearColorImage(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &black, 1, &kColorRange);
    vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT,
                       VK_ACCESS_2_TRANSFER_WRITE_BIT);
  }
  VkImageBlit blit{};
  blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.srcOffsets[1] = {int32_t(source.extent.width), int32_t(source.extent.height), 1};
  blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.dstOffsets[0] = begin;
  blit.dstOffsets[1] = end;
  bool same_size = end.x - begin.x == int32_t(source.extent.width) && end.y - begin.y == int32_t(source.extent.height);
  vkCmdBlitImage(cmd, source.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 1, &blit, same_size || !linear ? VK_FILTER_NEAREST : VK_FILTER_LINEAR);
}

// Full-screen triangle sampling the source, viewport = the letterbox rectangle, the rest
// cleared by the attachment's load op. Leaves the swapchain image in TRANSFER_DST.
void record_copy_pass(VkCommandBuffer cmd, const Presenter& p, const vk::Swapchain& sc, uint32_t index,
                      const vk::Image& source, VkImageLayout source_layout, VkOffset3D begin, VkOffset3D end) {
  VkImage target = sc.images[index];
  vk::image_barrier(cmd, target, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                    VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, kFirstUse, 0,
                    VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  vk::image_barrier(cmd, source.image, VK_IMAGE_ASPECT_COLOR_BIT, source_layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                    VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                    VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                    VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  color.imageView = sc.views[index];
  color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;  // the letterbox bars
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  color.clearValue.color = {{0.0f, 0.0f, 0.0f, 1.0f}};
  VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
  ri.renderArea = {{0, 0}, sc.extent};
  ri.layerCount = 1;
  ri.colorAttachmentCount = 1;
  ri.pColorAttachments = &color;
  vkCmdBeginRendering(cmd, &ri);
  gpu::PresentPush rect{};
  rect.offset = {float(begin.x), float(begin.y)};
  rect.size = {float(end.x - begin.x), float(end.y - begin.y)};
  VkViewport viewport{rect.offset.x, rect.offset.y, rect.size.x, rect.size.y, 0.0f, 1.0f};
  VkRect2D scissor{{begin.x, begin.y}, {uint32_t(end.x - begin.x), uint32_t(end.y - begin.y)}};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p.pipeline);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p.layout, 0, 1, &p.set, 0, nullptr);
  vkCmdPushConstants(cmd, p.layout, kPresentPushRange.stageFlags, 0, sizeof(rect), &rect);
  vkCmdDraw(cmd, 3, 1, 0, 0);
  vkCmdEndRendering(cmd);
  // The renderer's next frame writes the source after a barrier on the transfer stage:
  // chain the sampling reads into that stage.
  vk::image_barrier(cmd, source.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, 0,
                    VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, 0);
  vk::image_barrier(cmd, target, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                    VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                    VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
}

}  // namespace

bool overlay_byte_order(VkFormat format, bool* bgra) {
  switch (format) {
    case VK_FORMAT_B8G8R8A8_SRGB:
    case VK_FORMAT_B8G8R8A8_UNORM: *bgra = true; return true;
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_R8G8B8A8_UNORM: *bgra = false; return true;
    default: return false;
  }
}

bool can_present(vk::Context& ctx, VkFormat source_format, VkFormat swapchain_format, std::string* why) {
  VkFormatProperties src{}, dst{};
  vkGetPhysicalDeviceFormatProperties(ctx.physical, source_format, &src);
  vkGetPhysicalDeviceFormatProperties(ctx.physical, swapchain_format, &dst);
  if (!(src.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_SRC_BIT)) {
    *why = "the rendered image's format (VkFormat " + std::to_string(int(source_format)) + ") cannot be blitted from";
    return false;
  }
  if (!(dst.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_DST_BIT)) {
    *why = "the window's format (VkFormat " + std::to_string(int(swapchain_format)) + ") cannot be blitted to";
    return false;
  }
  return true;
}

void create_presenter(vk::Context& ctx, Presenter& p, const vk::Image& source, VkDeviceSize max_overlay_bytes) {
  VkFormatProperties props{};
  vkGetPhysicalDeviceFormatProperties(ctx.physical, source.format, &props);
  p.linear_blit = props.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
  for (Presenter::Frame& f : p.frames) {
    f.cmd = vk::allocate_command_buffer(ctx);
    f.done = vk::create_fence(ctx, true);  // the first wait on each slot returns at once
    VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VK_CHECK(vkCreateSemaphore(ctx.device, &sci, nullptr, &f.acquired));
    f.overlay = vk::create_buffer(ctx, std::max<VkDeviceSize>(max_overlay_bytes, 4), VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                  vk::MemoryUse::upload);
  }

  // Copy pass resources: one combined image sampler (the rendered image), a push-constant
  // viewport rectangle. The pipeline waits for the swapchain's format (present()).
  VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  sci.magFilter = sci.minFilter = p.linear_blit ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
  sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  VK_CHECK(vkCreateSampler(ctx.device, &sci, nullptr, &p.sampler));
  VkDescriptorSetLayoutCreateInfo slci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  slci.bindingCount = uint32_t(std::size(kPresentSetBindings));
  slci.pBindings = kPresentSetBindings;
  VK_CHECK(vkCreateDescriptorSetLayout(ctx.device, &slci, nullptr, &p.set_layout));
  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1};
  VkDescriptorPoolCreateInfo dpci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  dpci.maxSets = 1;
  dpci.poolSizeCount = 1;
  dpci.pPoolSizes = &size;
  VK_CHECK(vkCreateDescriptorPool(ctx.device, &dpci, nullptr, &p.pool));
  VkDescriptorSetAllocateInfo dsai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  dsai.descriptorPool = p.pool;
  dsai.descriptorSetCount = 1;
  dsai.pSetLayouts = &p.set_layout;
  VK_CHECK(vkAllocateDescriptorSets(ctx.device, &dsai, &p.set));
  VkDescriptorImageInfo image{p.sampler, source.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  write.dstSet = p.set;
  write.dstBinding = PRESENT_BINDING_RENDERED;
  write.descriptorCount = 1;
  write.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  write.pImageInfo = &image;
  vkUpdateDescriptorSets(ctx.device, 1, &write, 0, nullptr);
  p.layout = vk::create_pipeline_layout(ctx, p.set_layout, kPresentPushRange);
}

void destroy_presenter(vk::Context& ctx, Presenter& p) {
  vkDeviceWaitIdle(ctx.device);
  for (Presenter::Frame& f : p.frames) {
    if (f.cmd) vkFreeCommandBuffers(ctx.device, ctx.command_pool, 1, &f.cmd);
    vkDestroyFence(ctx.device, f.done, nullptr);
    vkDestroySemaphore(ctx.device, f.acquired, nullptr);
    vk::destroy_buffer(ctx, f.overlay);
    f = {};
  }
  vk::destroy_buffer(ctx, p.readback);
  vkDestroyPipeline(ctx.device, p.pipeline, nullptr);
  vkDestroyPipelineLayout(ctx.device, p.layout, nullptr);
  vkDestroyDescriptorPool(ctx.device, p.pool, nullptr);
  vkDestroyDescriptorSetLayout(ctx.device, p.set_layout, nullptr);
  vkDestroySampler(ctx.device, p.sampler, nullptr);
  p.pipeline = VK_NULL_HANDLE, p.layout = VK_NULL_HANDLE, p.pool = VK_NULL_HANDLE;
  p.set_layout = VK_NULL_HANDLE, p.sampler = VK_NULL_HANDLE;
}

namespace {

// The copy pass's pipeline, for the swapchain's format (first use, or the window changed it).
void ensure_copy_pipeline(vk::Context& ctx, Presenter& p, VkFormat format) {
  if (p.pipeline_format == format) return;
  vkDeviceWaitIdle(ctx.device);
  vkDestroyPipeline(ctx.device, p.pipeline, nullptr);
  vk::GraphicsPipelineDesc d;
  d.vertex = "present_vert";
  d.fragment = "present_frag";
  d.vertex_input = false;
  d.cull = VK_CULL_MODE_NONE;
  d.depth_test = d.depth_write = false;
  d.color_format = format;
  p.pipeline = vk::create_graphics_pipeline(ctx, p.layout, d);
  p.pipeline_format = format;
}

// O(1) per frame: a small panel, copied over the top-left corner of `target` (TRANSFER_DST).
void record_overlay(VkCommandBuffer cmd, const Presenter::Frame& f, const OverlayImage& overlay,
                    const vk::Swapchain& sc, VkImage target) {
  uint32_t w = std::min(overlay.width, sc.extent.width), h = std::min(overlay.height, sc.extent.height);
  std::memcpy(f.overlay.mapped, overlay.bytes.data(), std::min<size_t>(overlay.bytes.size(), f.overlay.size));
  vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  VkBufferImageCopy region{};
  region.bufferRowLength = overlay.width;
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {w, h, 1};
  vkCmdCopyBufferToImage(cmd, f.overlay.buffer, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
}

// Copies `target` (TRANSFER_DST) into the readback buffer; returns the layout it leaves.
VkImageLayout record_screenshot(vk::Context& ctx, VkCommandBuffer cmd, Presenter& p, const vk::Swapchain& sc,
                                VkImage target) {
  const VkDeviceSize shot_bytes = VkDeviceSize(sc.extent.width) * sc.extent.height * 4;
  if (p.readback.size < shot_bytes) {
    vk::destroy_buffer(ctx, p.readback);  // unused: every earlier screenshot waited for its frame
    p.readback = vk::create_buffer(ctx, shot_bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::readback);
  }
  vk::image_barrier(cmd, target, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                    VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {sc.extent.width, sc.extent.height, 1};
  vkCmdCopyImageToBuffer(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, p.readback.buffer, 1, &region);
  vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                     VK_ACCESS_2_HOST_READ_BIT);
  return VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
}

// After the frame's fence: the readback buffer as RGBA.
void read_screenshot(const Presenter& p, const vk::Swapchain& sc, FrameImage* screenshot) {
  const VkDeviceSize shot_bytes = VkDeviceSize(sc.extent.width) * sc.extent.height * 4;
  bool bgra = false;
  overlay_byte_order(sc.format, &bgra);
  screenshot->width = sc.extent.width;
  screenshot->height = sc.extent.height;
  screenshot->rgba.resize(shot_bytes);
  std::memcpy(screenshot->rgba.data(), p.readback.mapped, shot_bytes);
  if (bgra)
    for (size_t i = 0; i < shot_bytes; i += 4) std::swap(screenshot->rgba[i], screenshot->rgba[i + 2]);
}

void submit(vk::Context& ctx, const Presenter::Frame& f, VkSemaphore ready_to_present) {
  VkSemaphoreSubmitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  wait.semaphore = f.acquired;
  wait.stageMask = kFirstUse;
  VkSemaphoreSubmitInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  signal.semaphore = ready_to_present;
  signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  VkCommandBufferSubmitInfo cbi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cbi.commandBuffer = f.cmd;
  VkSubmitInfo2 si{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  si.waitSemaphoreInfoCount = 1;
  si.pWaitSemaphoreInfos = &wait;
  si.commandBufferInfoCount = 1;
  si.pCommandBufferInfos = &cbi;
  si.signalSemaphoreInfoCount = 1;
  si.pSignalSemaphoreInfos = &signal;
  VK_CHECK(vkQueueSubmit2(ctx.queue, 1, &si, f.done));
}

}  // namespace

PresentResult present(vk::Context& ctx, Presenter& p, const vk::Swapchain& sc, const vk::Image& source,
                      VkImageLayout source_layout, const OverlayImage* overlay, FrameImage* screenshot) {
  Presenter::Frame& f = p.frames[p.frame % Presenter::kFramesInFlight];
  // The slot's previous frame must be done before its command buffer, semaphore and
  // overlay buffer are reused; the other slot may still be in flight.
  VK_CHECK(vkWaitForFences(ctx.device, 1, &f.done, VK_TRUE, UINT64_MAX));
  uint32_t index = 0;
  VkResult acquired = vkAcquireNextImageKHR(ctx.device, sc.swapchain, UINT64_MAX, f.acquired, VK_NULL_HANDLE, &index);
  if (acquired == VK_ERROR_OUT_OF_DATE_KHR) return PresentResult::out_of_date;  // fence stays signalled
  if (acquired != VK_SUBOPTIMAL_KHR) VK_CHECK(acquired);
  VK_CHECK(vkResetFences(ctx.device, 1, &f.done));
  VkImage target = sc.images[index];

  VkCommandBuffer cmd = f.cmd;
  VK_CHECK(vkResetCommandBuffer(cmd, 0));
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(cmd, &bi));

  VkOffset3D end;
  VkOffset3D begin = fit_rect(source.extent, sc.extent, &end);
  if (p.copy_pass) {
    ensure_copy_pipeline(ctx, p, sc.format);
    record_copy_pass(cmd, p, sc, index, source, source_layout, begin, end);
  } else {
    record_blit(cmd, sc, target, source, source_layout, begin, end, p.linear_blit);
  }
  if (overlay && overlay->width > 0 && overlay->height > 0) record_overlay(cmd, f, *overlay, sc, target);
  VkImageLayout layout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  if (screenshot) layout = record_screenshot(ctx, cmd, p, sc, target);
  // Present reads the image after the semaphore; no access to make available here.
  vk::image_barrier(cmd, target, VK_IMAGE_ASPECT_COLOR_BIT, layout, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                    VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_NONE, 0);
  VK_CHECK(vkEndCommandBuffer(cmd));
  submit(ctx, f, sc.ready_to_present[index]);
  ++p.frame;

  if (screenshot) {
    VK_CHECK(vkWaitForFences(ctx.device, 1, &f.done, VK_TRUE, UINT64_MAX));
    read_screenshot(p, sc, screenshot);
  }

  VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  pi.waitSemaphoreCount = 1;
  pi.pWaitSemaphores = &sc.ready_to_present[index];
  pi.swapchainCount = 1;
  pi.pSwapchains = &sc.swapchain;
  pi.pImageIndices = &index;
  VkResult presented = vkQueuePresentKHR(ctx.queue, &pi);
  if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR || acquired == VK_SUBOPTIMAL_KHR)
    return PresentResult::out_of_date;
  VK_CHECK(presented);
  return PresentResult::presented;
}

}  // namespace forest
