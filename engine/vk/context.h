// Vulkan instance, device choice and the one graphics+compute queue the engine uses.
#pragma once
#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace forest::vk {

// Throws VkFailure (an internal error, exit code 1) when a Vulkan call fails; the message
// names the VkResult and, for out-of-memory and device loss, what happened.
struct VkFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};
void check(VkResult result, const char* what);
const char* result_name(VkResult result);
#define VK_CHECK(call) ::forest::vk::check((call), #call)

struct ContextOptions {
  // Khronos validation layer; every message of severity warning or error is counted.
  // Defaults to on when FOREST_VALIDATION=1 is set in the environment.
  bool validation = false;
  // With validation: also the layer's synchronization validation (hazards between commands:
  // missing barriers, read-after-write). Slower; tests turn it on for full frames.
  bool synchronization_validation = false;
  // Device index or case-insensitive name substring; empty = FOREST_DEVICE, then discrete first.
  std::string device;
  // Windowed use (forest walk): instance extensions the window system needs and a function
  // that makes the window's surface. The chosen queue must then also present to it, and the
  // device gets VK_KHR_swapchain. Empty = headless.
  std::vector<const char*> instance_extensions;
  std::function<VkSurfaceKHR(VkInstance)> create_surface;
};

struct DeviceReport {
  uint32_t index;
  std::string name;
  std::string type;
  std::string driver;
  uint32_t api_version;
};

struct Context {
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t queue_family = 0;
  VkCommandPool command_pool = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties{};
  VkPhysicalDeviceMemoryProperties memory{};
  uint32_t device_index = 0;
  bool validation = false;
  VkSurfaceKHR surface = VK_NULL_HANDLE;  // windowed contexts only; destroyed with the context
  bool fill_mode_non_solid = false;       // enabled when the device has it (wireframe view)
  bool geometry_shader = false;  // enabled when present: pulled leaves (else drawn instanced)
  bool pipeline_statistics = false;  // optional feature pipelineStatisticsQuery, enabled when present
  // Validation messages of severity warning or error seen so far (tests assert 0).
  std::atomic<uint32_t> validation_messages{0};
  std::string last_validation_message;
  // Bytes of device memory the engine's buffers and images hold now (vk::create_buffer and
  // the image functions add, vk::destroy_* subtract; swapchain images are the driver's).
  std::atomic<uint64_t> memory_in_use{0};
};

// Sanitizer builds only (a no-op otherwise): keeps the Vulkan drivers and layers loaded now
// in memory after the loader unloads them, so leak reports name them.
void pin_vulkan_libraries();
// All devices of the instance, as `forest info` lists them.
std::vector<DeviceReport> list_devices(VkInstance instance);
// Creates instance + device; throws InputError for a bad --device, VkFailure when no device
// has the features the engine relies on (the message names the missing ones).
void create_context(Context& ctx, const ContextOptions& options);
void destroy_context(Context& ctx);
// Validation layer on by default when FOREST_VALIDATION=1.
bool validation_from_env();

// The features the engine relies on, by name, and whether the chosen device has them.
std::vector<std::pair<std::string, bool>> required_features(VkPhysicalDevice physical);

// A primary command buffer from the context's pool, and a fence (`signaled`: the first wait
// returns at once).
VkCommandBuffer allocate_command_buffer(Context& ctx);
VkFence create_fence(Context& ctx, bool signaled);
// Resets `cmd` and begins it for one submission.
void begin_commands(VkCommandBuffer cmd);
// Submits one command buffer (no semaphores) to the context's queue; `fence` may be null.
void submit_commands(Context& ctx, VkCommandBuffer cmd, VkFence fence);

// Records and submits a one-off command buffer, waits for it.
template <typename F>
void submit_now(Context& ctx, F&& record);
VkCommandBuffer begin_one_shot(Context& ctx);
void end_one_shot(Context& ctx, VkCommandBuffer cmd);

template <typename F>
void submit_now(Context& ctx, F&& record) {
  VkCommandBuffer cmd = begin_one_shot(ctx);
  record(cmd);
  end_one_shot(ctx, cmd);
}

}  // namespace forest::vk
