#include "engine/render/render_targets.h"

#include <algorithm>

namespace forest {

RenderTargets create_render_targets(vk::Context& ctx, VkExtent2D extent, uint32_t samples) {
  VkSampleCountFlags supported = ctx.properties.limits.framebufferColorSampleCounts &
                                 ctx.properties.limits.framebufferDepthSampleCounts;
  while (samples > 1 && !(supported & samples)) samples >>= 1;
  RenderTargets t;
  t.extent = extent;
  t.samples = VkSampleCountFlagBits(std::max(samples, 1u));
  const bool msaa = t.samples > VK_SAMPLE_COUNT_1_BIT;
  t.color = vk::create_image(ctx, extent, kColorFormat,
                             VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                             VK_IMAGE_ASPECT_COLOR_BIT);
  if (msaa)
    t.color_msaa = vk::create_image(ctx, extent, kColorFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT,
                                    VK_IMAGE_ASPECT_COLOR_BIT, t.samples);
  // Multisampled depth resolves (sample 0, the one resolve mode every device has) into
  // depth_resolve for the pyramid.
  const VkImageUsageFlags depth_usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
  t.depth = vk::create_image(ctx, extent, kDepthFormat,
                             depth_usage | (msaa ? 0u : VkImageUsageFlags(VK_IMAGE_USAGE_SAMPLED_BIT)),
                             VK_IMAGE_ASPECT_DEPTH_BIT, t.samples);
  if (msaa)
    t.depth_resolve = vk::create_image(ctx, extent, kDepthFormat, depth_usage | VK_IMAGE_USAGE_SAMPLED_BIT,
                                       VK_IMAGE_ASPECT_DEPTH_BIT);
  return t;
}

void destroy_render_targets(vk::Context& ctx, RenderTargets& t) {
  for (vk::Image* image : {&t.color, &t.color_msaa, &t.depth, &t.depth_resolve}) vk::destroy_image(ctx, *image);
  t = {};
}

}  // namespace forest
