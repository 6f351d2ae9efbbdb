// The window's swapchain: FIFO (vsync, always available), an sRGB 8-bit format so a blit
// from the renderer's sRGB image keeps its bytes, images the present step writes by transfer.
#pragma once
#include <cstdint>
#include <vector>

#include "engine/vk/context.h"

namespace forest::vk {

struct Swapchain {
  VkSwapchainKHR swapchain = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkExtent2D extent{};
  std::vector<VkImage> images;
  std::vector<VkImageView> views;  // for the copy pass (render into the image)
  // One per image: signalled by the frame's submit, waited on by present. Per image (not
  // per frame in flight) because an image's previous present may still hold its semaphore.
  std::vector<VkSemaphore> ready_to_present;
  bool readback = false;  // images allow TRANSFER_SRC (screenshots of what is shown)
  uint32_t generation = 0;  // how many times it was (re)created
};

// (Re)creates the swapchain for a framebuffer of `framebuffer` pixels (used when the surface
// leaves the extent to the application). Returns false, creating nothing, while the surface
// extent is 0 × 0 (minimized window). Waits for the device to go idle before replacing.
bool create_swapchain(Context& ctx, Swapchain& swapchain, VkExtent2D framebuffer);
void destroy_swapchain(Context& ctx, Swapchain& swapchain);

}  // namespace forest::vk
