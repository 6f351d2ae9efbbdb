#include "engine/render/pyramid_overlay_pass.h"

#include "engine/vk/pipelines.h"

namespace forest {

PyramidOverlayPass create_pyramid_overlay_pass(vk::Context& ctx, VkPipelineLayout layout) {
  vk::GraphicsPipelineDesc d;
  d.vertex = "pyramid_overlay_vert";
  d.fragment = "pyramid_overlay_frag";
  d.vertex_input = false;
  d.cull = VK_CULL_MODE_NONE;
  d.depth_test = false;
  d.depth_write = false;
  d.color_format = kColorFormat;
  d.samples = VK_SAMPLE_COUNT_1_BIT;  // drawn into the resolved image
  return {vk::create_graphics_pipeline(ctx, layout, d)};
}

void destroy_pyramid_overlay_pass(vk::Context& ctx, PyramidOverlayPass& p) {
  vkDestroyPipeline(ctx.device, p.pipeline, nullptr);
  p = {};
}

VkRect2D pyramid_overlay_rect(VkExtent2D frame) {
  uint32_t w = frame.width / 2, h = frame.height / 2;
  return {{int32_t(frame.width - w), 0}, {w, h}};
}

void record_pyramid_overlay_pass(VkCommandBuffer cmd, const PyramidOverlayPass& p, VkPipelineLayout layout,
                                 VkDescriptorSet set, const RenderTargets& targets) {
  // The draw pass's writes (and resolve) of the colour image come first.
  vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                     VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  color.imageView = targets.color.view;
  color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  VkRect2D rect = pyramid_overlay_rect(targets.extent);
  VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
  ri.renderArea = rect;
  ri.layerCount = 1;
  ri.colorAttachmentCount = 1;
  ri.pColorAttachments = &color;
  vkCmdBeginRendering(cmd, &ri);
  VkViewport viewport{float(rect.offset.x), float(rect.offset.y), float(rect.extent.width), float(rect.extent.height),
                      0.0f, 1.0f};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &rect);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &set, 0, nullptr);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p.pipeline);
  vkCmdDraw(cmd, 3, 1, 0, 0);
  vkCmdEndRendering(cmd);
  // This frame's pyramid build rewrites what was just read.
  vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                     VK_ACCESS_2_NONE);
}

}  // namespace forest
