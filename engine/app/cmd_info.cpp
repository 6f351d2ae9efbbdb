#include <cstdio>

#include "engine/app/commands.h"
#include "engine/vk/context.h"

namespace forest::app {

int run_info(const InfoArgs& args) {
  vk::Context ctx;
  vk::ContextOptions options;
  options.device = args.device;
  options.validation = vk::validation_from_env();
  // Create the instance first so devices are listed even when the chosen one falls short.
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.apiVersion = VK_API_VERSION_1_3;
  VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ici.pApplicationInfo = &app;
  VkInstance instance;
  VK_CHECK(vkCreateInstance(&ici, nullptr, &instance));
  vk::pin_vulkan_libraries();
  std::printf("Vulkan devices:\n");
  for (const vk::DeviceReport& d : vk::list_devices(instance))
    std::printf("  [%u] %s (%s, Vulkan %u.%u.%u, %s)\n", d.index, d.name.c_str(), d.type.c_str(),
                VK_API_VERSION_MAJOR(d.api_version), VK_API_VERSION_MINOR(d.api_version),
                VK_API_VERSION_PATCH(d.api_version), d.driver.c_str());
  vkDestroyInstance(instance, nullptr);

  try {
    vk::create_context(ctx, options);
  } catch (const vk::VkFailure&) {
    vk::destroy_context(ctx);
    throw;
  }
  std::printf("chosen: [%u] %s\n", ctx.device_index, ctx.properties.deviceName);
  std::printf("features the engine relies on:\n");
  for (auto& [name, ok] : vk::required_features(ctx.physical)) std::printf("  %-42s %s\n", name.c_str(), ok ? "yes" : "MISSING");
  std::printf("  timestamp period: %.3f ns, max draw indirect count: %u\n", ctx.properties.limits.timestampPeriod,
              ctx.properties.limits.maxDrawIndirectCount);
  vk::destroy_context(ctx);
  return 0;
}

}  // namespace forest::app
