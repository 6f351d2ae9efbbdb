#include "engine/vk/context.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "generators/core/input_error.h"
#include "gpu_types.h"

#if defined(__SANITIZE_ADDRESS__)
#define FOREST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define FOREST_ASAN 1
#endif
#endif
#ifdef FOREST_ASAN
#include <dlfcn.h>
#include <link.h>
#endif

namespace forest::vk {

const char* result_name(VkResult result) {
  switch (result) {
    case VK_SUCCESS: return "VK_SUCCESS";
    case VK_NOT_READY: return "VK_NOT_READY";
    case VK_TIMEOUT: return "VK_TIMEOUT";
    case VK_INCOMPLETE: return "VK_INCOMPLETE";
    case VK_ERROR_OUT_OF_HOST_MEMORY: return "VK_ERROR_OUT_OF_HOST_MEMORY";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
    case VK_ERROR_INITIALIZATION_FAILED: return "VK_ERROR_INITIALIZATION_FAILED";
    case VK_ERROR_DEVICE_LOST: return "VK_ERROR_DEVICE_LOST";
    case VK_ERROR_MEMORY_MAP_FAILED: return "VK_ERROR_MEMORY_MAP_FAILED";
    case VK_ERROR_LAYER_NOT_PRESENT: return "VK_ERROR_LAYER_NOT_PRESENT";
    case VK_ERROR_EXTENSION_NOT_PRESENT: return "VK_ERROR_EXTENSION_NOT_PRESENT";
    case VK_ERROR_FEATURE_NOT_PRESENT: return "VK_ERROR_FEATURE_NOT_PRESENT";
    case VK_ERROR_INCOMPATIBLE_DRIVER: return "VK_ERROR_INCOMPATIBLE_DRIVER";
    case VK_ERROR_TOO_MANY_OBJECTS: return "VK_ERROR_TOO_MANY_OBJECTS";
    case VK_ERROR_FORMAT_NOT_SUPPORTED: return "VK_ERROR_FORMAT_NOT_SUPPORTED";
    case VK_ERROR_FRAGMENTED_POOL: return "VK_ERROR_FRAGMENTED_POOL";
    case VK_ERROR_OUT_OF_POOL_MEMORY: return "VK_ERROR_OUT_OF_POOL_MEMORY";
    default: return "VkResult";
  }
}

void check(VkResult result, const char* what) {
  if (result == VK_SUCCESS) return;
  std::string message = std::string("Vulkan call failed: ") + result_name(result) + " (" +
                        std::to_string(int(result)) + ")";
  if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY)
    message += ", out of GPU memory (try a smaller frame, fewer samples or fewer trees)";
  if (result == VK_ERROR_DEVICE_LOST)
    message += ", the GPU device was lost (driver crash, GPU reset or a hung submission)";
  throw VkFailure(message + ": " + what);
}

bool validation_from_env() {
  const char* v = std::getenv("FOREST_VALIDATION");
  return v && std::strcmp(v, "0") != 0 && *v;
}

namespace {

VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(
    VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
    const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  auto* ctx = static_cast<Context*>(user);
  if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
    ctx->validation_messages.fetch_add(1);
    ctx->last_validation_message = data->pMessage ? data->pMessage : "";
    std::fprintf(stderr, "validation %s: %s\n",
                 severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning",
                 data->pMessage ? data->pMessage : "");
  }
  return VK_FALSE;
}

const char* type_name(VkPhysicalDeviceType t) {
  switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
  }
}

int type_rank(VkPhysicalDeviceType t) {  // lower is preferred: discrete GPU first
  switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
    default: return 4;
  }
}

std::vector<VkPhysicalDevice> physical_devices(VkInstance instance) {
  uint32_t n = 0;
  VK_CHECK(vkEnumeratePhysicalDevices(instance, &n, nullptr));
  std::vector<VkPhysicalDevice> out(n);
  VK_CHECK(vkEnumeratePhysicalDevices(instance, &n, out.data()));
  return out;
}

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

uint32_t choose_device(VkInstance instance, std::string wanted) {
  std::vector<DeviceReport> devices = list_devices(instance);
  if (devices.empty()) throw VkFailure("no Vulkan device found (is mesa-vulkan-drivers installed?)");
  const char* source = "--device";
  if (wanted.empty()) {
    if (const char* env = std::getenv("FOREST_DEVICE"); env && *env) {
      wanted = env;
      source = "FOREST_DEVICE";
    }
  }
  if (!wanted.empty()) {
    bool numeric = std::all_of(wanted.begin(), wanted.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
    if (numeric) {
      unsigned long i = std::strtoul(wanted.c_str(), nullptr, 10);
      if (i < devices.size()) return uint32_t(i);
    } else {
      for (const DeviceReport& d : devices)
        if (lower(d.name).find(lower(wanted)) != std::string::npos) return d.index;
    }
    std::string names;
    for (const DeviceReport& d : devices)
      names += (names.empty() ? "" : ", ") + std::to_string(d.index) + " " + d.name;
    throw InputError(source, 0, "", "no Vulkan device matches '" + wanted + "' (devices: " + names + ")");
  }
  VkPhysicalDeviceProperties p{};
  std::vector<VkPhysicalDevice> phys = physical_devices(instance);
  uint32_t best = 0;
  int best_rank = 99;
  for (uint32_t i = 0; i < phys.size(); ++i) {
    vkGetPhysicalDeviceProperties(phys[i], &p);
    int r = type_rank(p.deviceType);
    if (r < best_rank) best_rank = r, best = i;
  }
  return best;
}

}  // namespace

std::vector<DeviceReport> list_devices(VkInstance instance) {
  std::vector<DeviceReport> out;
  std::vector<VkPhysicalDevice> phys = physical_devices(instance);
  for (uint32_t i = 0; i < phys.size(); ++i) {
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceProperties2 p{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &driver};
    vkGetPhysicalDeviceProperties2(phys[i], &p);
    out.push_back({i, p.properties.deviceName, type_name(p.properties.deviceType),
                   std::string(driver.driverName) + " " + driver.driverInfo,
                   p.properties.apiVersion});
  }
  return out;
}

std::vector<std::pair<std::string, bool>> required_features(VkPhysicalDevice physical) {
  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &f13};
  VkPhysicalDeviceVulkan11Features f11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES, &f12};
  VkPhysicalDeviceFeatures2 f{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f11};
  vkGetPhysicalDeviceFeatures2(physical, &f);
  VkPhysicalDeviceVulkan13Properties p13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_PROPERTIES};
  VkPhysicalDeviceVulkan11Properties p11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_PROPERTIES, &p13};
  VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &p11};
  vkGetPhysicalDeviceProperties2(physical, &p2);
  const VkPhysicalDeviceProperties& p = p2.properties;
  const VkSubgroupFeatureFlags subgroup_ops = VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_ARITHMETIC_BIT;
  return {
      {"Vulkan 1.3", p.apiVersion >= VK_API_VERSION_1_3},
      {"drawIndirectCount", bool(f12.drawIndirectCount)},
      {"shaderDrawParameters", bool(f11.shaderDrawParameters)},
      {"samplerFilterMinmax", bool(f12.samplerFilterMinmax)},
      {"dynamicRendering", bool(f13.dynamicRendering)},
      {"synchronization2", bool(f13.synchronization2)},
      {"timestamps (timestampComputeAndGraphics)", bool(p.limits.timestampComputeAndGraphics)},
      {"multiDrawIndirect", bool(f.features.multiDrawIndirect)},
      {"drawIndirectFirstInstance", bool(f.features.drawIndirectFirstInstance)},
      {"maintenance4", bool(f13.maintenance4)},
      // tail_cull.comp: prefix sums by subgroup, over full subgroups that tile its workgroup.
      {"subgroup arithmetic in compute shaders", (p11.subgroupSupportedStages & VK_SHADER_STAGE_COMPUTE_BIT) != 0 &&
                                                     (p11.subgroupSupportedOperations & subgroup_ops) == subgroup_ops},
      {"computeFullSubgroups", bool(f13.subgroupSizeControl) && bool(f13.computeFullSubgroups)},
      {"maxSubgroupSize dividing " + std::to_string(TAIL_GROUP_SIZE),
       p13.maxSubgroupSize > 0 && TAIL_GROUP_SIZE % p13.maxSubgroupSize == 0},
  };
}

void pin_vulkan_libraries() {
#ifdef FOREST_ASAN
  // The loader dlcloses drivers and layers at vkDestroyInstance; LeakSanitizer runs at exit and
  // then sees their process-lifetime allocations from an "<unknown module>", which no
  // suppression can name (tests/lsan.supp). Pinned with RTLD_NODELETE, they keep their names.
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void*) {
        const char* name = info->dlpi_name;
        if (name && (std::strstr(name, "libvulkan_") || std::strstr(name, "libVkLayer_")))
          dlopen(name, RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
        return 0;
      },
      nullptr);
#endif
}

namespace {

void require_validation_layer() {
  uint32_t n = 0;
  vkEnumerateInstanceLayerProperties(&n, nullptr);
  std::vector<VkLayerProperties> props(n);
  vkEnumerateInstanceLayerProperties(&n, props.data());
  bool found = std::any_of(props.begin(), props.end(), [](const VkLayerProperties& l) {
    return std::strcmp(l.layerName, "VK_LAYER_KHRONOS_validation") == 0;
  });
  if (!found)
    throw VkFailure("validation requested but VK_LAYER_KHRONOS_validation is not installed "
                    "(apt-get install vulkan-validationlayers)");
}

// Warnings and errors of every message type, counted into `ctx` (on_validation_message).
VkDebugUtilsMessengerCreateInfoEXT messenger_info_for(Context& ctx) {
  VkDebugUtilsMessengerCreateInfoEXT messenger_info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  messenger_info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                   VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messenger_info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messenger_info.pfnUserCallback = on_validation_message;
  messenger_info.pUserData = &ctx;
  return messenger_info;
}

// The instance, with the validation layer and its messenger when ctx.validation (and the
// layer's synchronization validation when asked for).
void create_instance(Context& ctx, const ContextOptions& options) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "forest";
  app.pEngineName = "forest";
  app.apiVersion = VK_API_VERSION_1_3;

  std::vector<const char*> layers, extensions;
  if (ctx.validation) {
    require_validation_layer();
    layers.push_back("VK_LAYER_KHRONOS_validation");
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }
  extensions.insert(extensions.end(), options.instance_extensions.begin(), options.instance_extensions.end());
  // Synchronization validation (VK_EXT_validation_features, provided by the layer itself).
  const VkValidationFeatureEnableEXT sync_validation = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  VkValidationFeaturesEXT validation_features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  validation_features.enabledValidationFeatureCount = 1;
  validation_features.pEnabledValidationFeatures = &sync_validation;
  const bool sync = ctx.validation && options.synchronization_validation;
  if (sync) extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
  VkDebugUtilsMessengerCreateInfoEXT messenger_info = messenger_info_for(ctx);

  VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ici.pNext = ctx.validation ? &messenger_info : nullptr;  // also covers create/destroy
  if (sync) {
    validation_features.pNext = &messenger_info;
    ici.pNext = &validation_features;
  }
  ici.pApplicationInfo = &app;
  ici.enabledLayerCount = uint32_t(layers.size());
  ici.ppEnabledLayerNames = layers.data();
  ici.enabledExtensionCount = uint32_t(extensions.size());
  ici.ppEnabledExtensionNames = extensions.data();
  VkResult r = vkCreateInstance(&ici, nullptr, &ctx.instance);
  if (r == VK_ERROR_INCOMPATIBLE_DRIVER)
    throw VkFailure("no Vulkan 1.3 driver found (install mesa-vulkan-drivers for lavapipe)");
  VK_CHECK(r);
  if (ctx.validation) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(ctx.instance, "vkCreateDebugUtilsMessengerEXT"));
    VK_CHECK(create(ctx.instance, &messenger_info, nullptr, &ctx.messenger));
  }
}

// The device of --device (or the default choice), refused when it lacks a feature the
// engine relies on.
void choose_physical_device(Context& ctx, const std::string& device) {
  ctx.device_index = choose_device(ctx.instance, device);
  ctx.physical = physical_devices(ctx.instance)[ctx.device_index];
  vkGetPhysicalDeviceProperties(ctx.physical, &ctx.properties);
  vkGetPhysicalDeviceMemoryProperties(ctx.physical, &ctx.memory);

  std::string missing;
  for (auto& [name, ok] : required_features(ctx.physical))
    if (!ok) missing += (missing.empty() ? "" : ", ") + name;
  if (!missing.empty())
    throw VkFailure(std::string("device '") + ctx.properties.deviceName +
                    "' lacks features the engine relies on: " + missing);
}

// The first queue family with graphics, compute and timestamps (that can also present to
// the window's surface, when there is one).
uint32_t choose_queue_family(const Context& ctx) {
  uint32_t nq = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(ctx.physical, &nq, nullptr);
  std::vector<VkQueueFamilyProperties> families(nq);
  vkGetPhysicalDeviceQueueFamilyProperties(ctx.physical, &nq, families.data());
  for (uint32_t i = 0; i < nq; ++i) {
    VkBool32 present = VK_TRUE;  // headless: nothing to present to
    if (ctx.surface) VK_CHECK(vkGetPhysicalDeviceSurfaceSupportKHR(ctx.physical, i, ctx.surface, &present));
    if ((families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) && (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) &&
        families[i].timestampValidBits > 0 && present)
      return i;
  }
  throw VkFailure(ctx.surface ? "no graphics+compute queue with timestamps that can present to the window"
                              : "no graphics+compute queue with timestamps on the chosen device");
}

// The logical device with one queue of ctx.queue_family, the features the engine relies
// on, the optional ones the device has, and VK_KHR_swapchain when windowed.
void create_device(Context& ctx) {
  float priority = 1.0f;
  VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qci.queueFamilyIndex = ctx.queue_family;
  qci.queueCount = 1;
  qci.pQueuePriorities = &priority;

  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  f13.dynamicRendering = VK_TRUE;
  f13.synchronization2 = VK_TRUE;
  f13.maintenance4 = VK_TRUE;  // required by 1.3; glslang emits LocalSizeId for SPIR-V 1.6
  f13.subgroupSizeControl = VK_TRUE;  // required by 1.3: full subgroups for tail_cull.comp
  f13.computeFullSubgroups = VK_TRUE;
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &f13};
  f12.drawIndirectCount = VK_TRUE;
  f12.samplerFilterMinmax = VK_TRUE;
  VkPhysicalDeviceVulkan11Features f11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES, &f12};
  f11.shaderDrawParameters = VK_TRUE;
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f11};
  features.features.multiDrawIndirect = VK_TRUE;
  features.features.drawIndirectFirstInstance = VK_TRUE;
  VkPhysicalDeviceFeatures available{};
  vkGetPhysicalDeviceFeatures(ctx.physical, &available);
  ctx.fill_mode_non_solid = available.fillModeNonSolid;  // optional: only the wireframe view uses it
  features.features.fillModeNonSolid = available.fillModeNonSolid;
  // Optional: pulled leaves make their triangles in a geometry shader (leaf_card.geom); without
  // one they are drawn as instances of the card.
  ctx.geometry_shader = available.geometryShader == VK_TRUE;
  features.features.geometryShader = available.geometryShader;
  // Optional: pipeline-statistics queries (`forest render --stats` prints "n/a" without).
  ctx.pipeline_statistics = available.pipelineStatisticsQuery == VK_TRUE;
  features.features.pipelineStatisticsQuery = available.pipelineStatisticsQuery;

  const char* swapchain_extension = VK_KHR_SWAPCHAIN_EXTENSION_NAME;
  VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &features};
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &qci;
  dci.enabledExtensionCount = ctx.surface ? 1 : 0;
  dci.ppEnabledExtensionNames = &swapchain_extension;
  VK_CHECK(vkCreateDevice(ctx.physical, &dci, nullptr, &ctx.device));
}

}  // namespace

void create_context(Context& ctx, const ContextOptions& options) {
  ctx.validation = options.validation;
  create_instance(ctx, options);
  if (options.create_surface) ctx.surface = options.create_surface(ctx.instance);
  choose_physical_device(ctx, options.device);
  ctx.queue_family = choose_queue_family(ctx);
  create_device(ctx);
  pin_vulkan_libraries();
  vkGetDeviceQueue(ctx.device, ctx.queue_family, 0, &ctx.queue);

  VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pci.queueFamilyIndex = ctx.queue_family;
  VK_CHECK(vkCreateCommandPool(ctx.device, &pci, nullptr, &ctx.command_pool));
}

void destroy_context(Context& ctx) {
  if (ctx.device) {
    vkDeviceWaitIdle(ctx.device);
    vkDestroyCommandPool(ctx.device, ctx.command_pool, nullptr);
    vkDestroyDevice(ctx.device, nullptr);
  }
  if (ctx.messenger) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(ctx.instance, "vkDestroyDebugUtilsMessengerEXT"));
    destroy(ctx.instance, ctx.messenger, nullptr);
  }
  if (ctx.surface) vkDestroySurfaceKHR(ctx.instance, ctx.surface, nullptr);
  if (ctx.instance) vkDestroyInstance(ctx.instance, nullptr);
  ctx.surface = VK_NULL_HANDLE;
  ctx.device = VK_NULL_HANDLE;
  ctx.instance = VK_NULL_HANDLE;
  ctx.messenger = VK_NULL_HANDLE;
}

VkCommandBuffer allocate_command_buffer(Context& ctx) {
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = ctx.command_pool;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCommandBuffer cmd;
  VK_CHECK(vkAllocateCommandBuffers(ctx.device, &ai, &cmd));
  return cmd;
}

VkFence create_fence(Context& ctx, bool signaled) {
  VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  if (signaled) fci.flags = VK_FENCE_CREATE_SIGNALED_BIT;
  VkFence fence;
  VK_CHECK(vkCreateFence(ctx.device, &fci, nullptr, &fence));
  return fence;
}

void begin_commands(VkCommandBuffer cmd) {
  VK_CHECK(vkResetCommandBuffer(cmd, 0));
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(cmd, &bi));
}

VkCommandBuffer begin_one_shot(Context& ctx) {
  VkCommandBuffer cmd = allocate_command_buffer(ctx);
  begin_commands(cmd);
  return cmd;
}

void submit_commands(Context& ctx, VkCommandBuffer cmd, VkFence fence) {
  VkCommandBufferSubmitInfo cbi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cbi.commandBuffer = cmd;
  VkSubmitInfo2 si{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  si.commandBufferInfoCount = 1;
  si.pCommandBufferInfos = &cbi;
  VK_CHECK(vkQueueSubmit2(ctx.queue, 1, &si, fence));
}

void end_one_shot(Context& ctx, VkCommandBuffer cmd) {
  VK_CHECK(vkEndCommandBuffer(cmd));
  VkFence fence = create_fence(ctx, false);
  submit_commands(ctx, cmd, fence);
  VK_CHECK(vkWaitForFences(ctx.device, 1, &fence, VK_TRUE, UINT64_MAX));
  vkDestroyFence(ctx.device, fence, nullptr);
  vkFreeCommandBuffers(ctx.device, ctx.command_pool, 1, &cmd);
}

}  // namespace forest::vk
