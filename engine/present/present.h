// Present step of `forest walk`: the renderer keeps rendering into its own image; this
// copies that image into a swapchain image (blit, scaled to fit with the aspect kept, bars
// cleared; or, where the window's format cannot be blitted to, a full-screen-triangle copy
// pass that samples it), puts the HUD panel over its top-left corner and presents. Two frames in flight,
// each with its own command buffer, fence, acquire semaphore and HUD upload buffer.
#pragma once
#include <cstdint>
#include <vector>

#include "engine/present/hud.h"
#include "engine/render/renderer.h"
#include "engine/vk/resources.h"
#include "engine/vk/swapchain.h"
#include "gpu_types.h"

namespace forest {

// The copy pass's set (present.frag) and push constants; tests/unit/test_gpu_interface.cpp
// checks the compiled shaders against them.
inline constexpr VkDescriptorSetLayoutBinding kPresentSetBindings[] = {
    {PRESENT_BINDING_RENDERED, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
};
inline constexpr VkPushConstantRange kPresentPushRange{VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(gpu::PresentPush)};

struct Presenter {
  static constexpr uint32_t kFramesInFlight = 2;
  struct Frame {
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkFence done = VK_NULL_HANDLE;          // signalled when the frame's commands finished
    VkSemaphore acquired = VK_NULL_HANDLE;  // swapchain image ready to be written
    vk::Buffer overlay;                     // HUD pixels of this frame (host-visible)
  };
  Frame frames[kFramesInFlight];
  uint32_t frame = 0;  // frames presented so far; frames[frame % kFramesInFlight] is next
  vk::Buffer readback;  // screenshots of the swapchain image
  bool linear_blit = false;  // source format can be filtered when scaled

  // Copy pass (shaders/present.*), used instead of the blit when `copy_pass` is set.
  bool copy_pass = false;
  VkSampler sampler = VK_NULL_HANDLE;
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VkDescriptorSet set = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkFormat pipeline_format = VK_FORMAT_UNDEFINED;
};

// `max_overlay_bytes`: the largest OverlayImage ever passed to present().
// `source`: the image present() will be given (the renderer's; read by the copy pass).
void create_presenter(vk::Context& ctx, Presenter& presenter, const vk::Image& source, VkDeviceSize max_overlay_bytes);
void destroy_presenter(vk::Context& ctx, Presenter& presenter);

// Whether a blit can write `swapchain_format` from `source_format`; when not, the message
// says why and the copy pass must be used.
bool can_present(vk::Context& ctx, VkFormat source_format, VkFormat swapchain_format, std::string* why);
// Whether an OverlayImage can be copied as raw bytes into images of this format.
bool overlay_byte_order(VkFormat swapchain_format, bool* bgra);

enum class PresentResult { presented, out_of_date };

// Presents `source` (left by the renderer in `source_layout`). `screenshot`: when given,
// waits for the frame and fills it with the swapchain image as shown (HUD included), in RGBA.
// out_of_date: the swapchain must be recreated (resize) before the next frame; the frame
// may or may not have been shown.
PresentResult present(vk::Context& ctx, Presenter& presenter, const vk::Swapchain& swapchain,
                      const vk::Image& source, VkImageLayout source_layout, const OverlayImage* overlay,
                      FrameImage* screenshot);

}  // namespace forest
