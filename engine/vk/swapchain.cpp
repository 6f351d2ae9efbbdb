#include "engine/vk/swapchain.h"

#include <algorithm>

namespace forest::vk {

namespace {

// sRGB formats first: the renderer's image is sRGB, so a blit between two sRGB formats
// decodes and re-encodes losslessly and the window shows exactly the rendered bytes.
VkSurfaceFormatKHR choose_format(VkPhysicalDevice physical, VkSurfaceKHR surface) {
  uint32_t n = 0;
  VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &n, nullptr));
  std::vector<VkSurfaceFormatKHR> formats(n);
  VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &n, formats.data()));
  if (formats.empty()) throw VkFailure("the window surface offers no formats");
  for (VkFormat wanted : {VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_R8G8B8A8_SRGB})
    for (const VkSurfaceFormatKHR& f : formats)
      if (f.format == wanted && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) return f;
  return formats[0];
}

}  // namespace

bool create_swapchain(Context& ctx, Swapchain& sc, VkExtent2D framebuffer) {
  VkSurfaceCapabilitiesKHR caps{};
  VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(ctx.physical, ctx.surface, &caps));
  VkExtent2D extent = caps.currentExtent;
  if (extent.width == UINT32_MAX) {  // the surface takes the size of the swapchain
    extent.width = std::clamp(framebuffer.width, caps.minImageExtent.width, caps.maxImageExtent.width);
    extent.height = std::clamp(framebuffer.height, caps.minImageExtent.height, caps.maxImageExtent.height);
  }
  if (extent.width == 0 || extent.height == 0) return false;  // minimized

  const VkImageUsageFlags needed = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  if ((caps.supportedUsageFlags & needed) != needed)
    throw VkFailure("the window's swapchain images cannot be written by transfer (TRANSFER_DST)");
  VkSurfaceFormatKHR format = choose_format(ctx.physical, ctx.surface);
  uint32_t image_count = caps.minImageCount + 1;
  if (caps.maxImageCount > 0) image_count = std::min(image_count, caps.maxImageCount);

  VkSwapchainCreateInfoKHR ci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  ci.surface = ctx.surface;
  ci.minImageCount = image_count;
  ci.imageFormat = format.format;
  ci.imageColorSpace = format.colorSpace;
  ci.imageExtent = extent;
  ci.imageArrayLayers = 1;
  // COLOR_ATTACHMENT is always supported; the copy pass renders into the images.
  ci.imageUsage = needed | VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  ci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ci.preTransform = (caps.supportedTransforms & VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR)
                        ? VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR
                        : caps.currentTransform;
  ci.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
  for (VkCompositeAlphaFlagBitsKHR a : {VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR, VK_COMPOSITE_ALPHA_INHERIT_BIT_KHR,
                                        VK_COMPOSITE_ALPHA_PRE_MULTIPLIED_BIT_KHR,
                                        VK_COMPOSITE_ALPHA_POST_MULTIPLIED_BIT_KHR})
    if (caps.supportedCompositeAlpha & a) {
      ci.compositeAlpha = a;
      break;
    }
  ci.presentMode = VK_PRESENT_MODE_FIFO_KHR;  // the one mode every driver has; no tearing
  ci.clipped = VK_TRUE;
  ci.oldSwapchain = sc.swapchain;

  vkDeviceWaitIdle(ctx.device);  // the old images and semaphores may still be in use
  VkSwapchainKHR created;
  VK_CHECK(vkCreateSwapchainKHR(ctx.device, &ci, nullptr, &created));
  uint32_t generation = sc.generation;
  destroy_swapchain(ctx, sc);
  sc.swapchain = created;
  sc.format = format.format;
  sc.extent = extent;
  sc.readback = caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  sc.generation = generation + 1;
  uint32_t n = 0;
  VK_CHECK(vkGetSwapchainImagesKHR(ctx.device, created, &n, nullptr));
  sc.images.resize(n);
  VK_CHECK(vkGetSwapchainImagesKHR(ctx.device, created, &n, sc.images.data()));
  for (VkImage image : sc.images) {
    VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vci.image = image;
    vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vci.format = sc.format;
    vci.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VK_CHECK(vkCreateImageView(ctx.device, &vci, nullptr, &sc.views.emplace_back()));
  }
  sc.ready_to_present.resize(n);
  VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  for (VkSemaphore& s : sc.ready_to_present) VK_CHECK(vkCreateSemaphore(ctx.device, &sci, nullptr, &s));
  return true;
}

void destroy_swapchain(Context& ctx, Swapchain& sc) {
  for (VkSemaphore s : sc.ready_to_present) vkDestroySemaphore(ctx.device, s, nullptr);
  sc.ready_to_present.clear();
  for (VkImageView v : sc.views) vkDestroyImageView(ctx.device, v, nullptr);
  sc.views.clear();
  sc.images.clear();
  if (sc.swapchain) vkDestroySwapchainKHR(ctx.device, sc.swapchain, nullptr);
  sc.swapchain = VK_NULL_HANDLE;
}

}  // namespace forest::vk
