// Debug overlay pass: draws the depth pyramid that this frame's occlusion test reads into
// the top-right quarter of the frame (shaders/pyramid_overlay.*), so what the cull pass can
// hide behind is visible (`forest render --overlay pyramid`, `forest walk` key Y). Only with
// occlusion on: without it the pyramid holds nothing. Coverage renders never draw it.
#pragma once

#include "engine/render/descriptor_table.h"
#include "engine/render/render_targets.h"
#include "gpu_types.h"

namespace forest {

struct PyramidOverlayPass {
  VkPipeline pipeline = VK_NULL_HANDLE;
};

inline constexpr Binding kPyramidOverlayBindings[] = {
    {BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_SHADER_STAGE_FRAGMENT_BIT},
    {BINDING_DEPTH_PYRAMID, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT},
};

PyramidOverlayPass create_pyramid_overlay_pass(vk::Context& ctx, VkPipelineLayout layout);
void destroy_pyramid_overlay_pass(vk::Context& ctx, PyramidOverlayPass& pass);

// The rectangle of the frame the overlay covers: the top-right quarter.
VkRect2D pyramid_overlay_rect(VkExtent2D frame);

// After the draw pass (colour in COLOR_ATTACHMENT_OPTIMAL), before this frame's pyramid is
// built: draws over the resolved colour image, then orders its reads of the pyramid before
// the pyramid's next writes.
void record_pyramid_overlay_pass(VkCommandBuffer cmd, const PyramidOverlayPass& pass, VkPipelineLayout layout,
                                 VkDescriptorSet set, const RenderTargets& targets);

}  // namespace forest
