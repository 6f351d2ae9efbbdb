#include <chrono>
#include <cstdio>

#include "engine/app/commands.h"
#include "engine/render/image_io.h"
#include "engine/render/renderer.h"
#include "engine/scene/scene.h"

namespace forest::app {

int run_render(const RenderArgs& args) {
  using clock = std::chrono::steady_clock;
  auto t0 = clock::now();
  std::filesystem::path out = args.out;
  check_output_path(out, "--out");
  SceneDesc desc = load_scene_file(args.scene);
  if (args.width) desc.width = *args.width;
  if (args.height) desc.height = *args.height;
  Scene scene = build_scene(desc);
  if (scene.placement_shortfall > 0)
    std::fprintf(stderr, "forest: %s: placement: only %u of %u trees found room (min_spacing / radius / max_slope)\n",
                 args.scene.c_str(), desc.placement.count - scene.placement_shortfall, desc.placement.count);
  auto t_scene = clock::now();

  vk::Context ctx;
  vk::ContextOptions options;
  options.device = args.device;
  options.validation = args.validate || vk::validation_from_env();
  int code = 0;
  try {
    vk::create_context(ctx, options);
    FrameImage image;
    FrameStats stats;
    bool settings_occlusion = args.occlusion.value_or(desc.occlusion);
    auto t_render = clock::now();
    {
      Renderer renderer(ctx, scene, desc.width, desc.height, desc.samples);
      t_render = clock::now();
      FrameSettings settings = scene_frame_settings(desc);
      if (args.occlusion) settings.occlusion = *args.occlusion;
      // Occlusion feeds back from one frame to the next: a still picture shows the steady
      // state, after the hidden trees have thinned out (kWarmupFrames from the same camera).
      constexpr int kWarmupFrames = 5;
      for (int i = 0; settings.occlusion && i < kWarmupFrames; ++i) renderer.render(desc.camera, nullptr, settings);
      stats = renderer.render(desc.camera, &image, settings);
    }
    auto t_done = clock::now();
    if (ctx.validation_messages > 0) {
      std::fprintf(stderr, "forest: %u Vulkan validation message(s); no image written\n", ctx.validation_messages.load());
      code = 1;
    } else {
      write_image(image, out);
      auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
      std::printf("wrote %s (%ux%u) on %s: %u trees, %u visible, %u leaves drawn\n", out.c_str(), desc.width,
                  desc.height, ctx.properties.deviceName, stats.instances, stats.branch_draws, stats.leaves_drawn);
      if (args.stats)
        std::printf("time: scene %.0f ms (generate + place), upload %.0f ms, frame %.1f ms wall; "
                    "GPU cull %.2f ms, draw %.1f ms, frame %.1f ms\n",
                    ms(t0, t_scene), ms(t_scene, t_render), ms(t_render, t_done), stats.cull_ms, stats.draw_ms,
                    stats.frame_ms);
      if (args.stats)
        std::printf("branches: %u triangles drawn; trees per LOD: %u %u %u %u; mean lambda %.3f\n",
                    stats.branch_triangles, stats.lod_draws[0], stats.lod_draws[1], stats.lod_draws[2],
                    stats.lod_draws[3], stats.mean_lambda);
      if (args.stats && settings_occlusion)
        std::printf("occlusion: %u trees culled, %u leaves and %u triangles saved; GPU pyramid %.2f ms\n",
                    stats.occluded_instances, stats.leaves_saved, stats.triangles_saved, stats.pyramid_ms);
    }
  } catch (...) {
    vk::destroy_context(ctx);
    throw;
  }
  vk::destroy_context(ctx);
  return code;
}

}  // namespace forest::app
