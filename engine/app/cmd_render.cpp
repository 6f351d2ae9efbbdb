#include <chrono>
#include <cstdio>

#include "engine/tools/bake/species_cache.h"
#include "engine/app/commands.h"
#include "engine/present/image_io.h"
#include "engine/render/renderer.h"
#include "engine/scene/camera_path.h"
#include "engine/scene/scene.h"
#include "generators/core/input_error.h"

namespace forest::app {

namespace {

void print_pipeline_stats(const char* pass, const PipelineStats& s) {
  if (!s.available) {
    std::printf("pipeline statistics (%s): n/a\n", pass);
    return;
  }
  if (std::string(pass) == "cull") {
    std::printf("pipeline statistics (cull): CS invocations %llu\n", (unsigned long long)s.cs_invocations);
    return;
  }
  std::printf("pipeline statistics (%s): IA vertices %llu, IA primitives %llu, VS invocations %llu, "
              "clipping in %llu / out %llu primitives, FS invocations %llu\n",
              pass, (unsigned long long)s.ia_vertices, (unsigned long long)s.ia_primitives,
              (unsigned long long)s.vs_invocations, (unsigned long long)s.clip_invocations,
              (unsigned long long)s.clip_primitives, (unsigned long long)s.fs_invocations);
}

}  // namespace

int run_render(const RenderArgs& args) {
  using clock = std::chrono::steady_clock;
  auto t0 = clock::now();
  std::filesystem::path out = args.out;
  check_output_path(out, "--out");
  SceneDesc desc = load_scene_file(args.scene);
  if (args.width) desc.width = *args.width;
  if (args.height) desc.height = *args.height;
  if (!args.mode.empty())
    desc.prune_mode = args.mode == "cook" ? PRUNE_COOK : args.mode == "opt" ? PRUNE_OPT : PRUNE_FULL;
  if (!args.view.empty()) {
    desc.lambda_view = args.view == "lambda";
    desc.mask_view = args.view == "mask";
  }
  CameraDesc camera = desc.camera;
  if (!args.path.empty()) {
    const CameraPath* path = find_path(desc, args.path);
    if (!path) throw InputError(args.scene, 0, "--path", "no [[path]] named '" + args.path + "'");
    double t = args.time ? *args.time : args.frame ? double(*args.frame) / path->fps : 0.0;
    camera = camera_at(*path, path->keys.front().time + float(t), desc.camera);
  } else if (args.frame || args.time) {
    throw InputError(args.scene, 0, args.frame ? "--frame" : "--time", "needs --path NAME");
  }
  SpeciesCacheOptions cache;  // presets: generated and baked on first use, then loaded
  cache.dir = args.cache;
  cache.log = [](const std::string& line) { std::printf("%s\n", line.c_str()), std::fflush(stdout); };
  SceneBuildOptions build;
  build.species = cached_species_source(cache);
  Scene scene = build_scene(desc, build);
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
      for (int i = 0; settings.occlusion && i < kWarmupFrames; ++i) renderer.render(camera, nullptr, settings);
      stats = renderer.render(camera, &image, settings);
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
      if (args.stats) {
        std::printf("branches: %u triangles drawn; trees per LOD: %u %u %u %u; mean lambda %.3f\n",
                    stats.branch_triangles, stats.lod_draws[0], stats.lod_draws[1], stats.lod_draws[2],
                    stats.lod_draws[3], stats.mean_lambda);
        FullDetailSize full = full_detail_size(scene);
        std::printf("instances visible %u of %u; leaves drawn %u; full detail: %llu triangles, %llu vertices "
                    "(%.2f B as input assembly counts them, 3 per triangle)\n",
                    stats.branch_draws, stats.instances, stats.leaves_drawn, (unsigned long long)full.triangles,
                    (unsigned long long)full.vertices, 3e-9 * double(full.triangles));
        std::printf("CPU per frame (constants + record + submit): %.3f ms\n", stats.cpu_submit_ms);
        print_pipeline_stats("cull", stats.cull_pipeline);
        print_pipeline_stats("draw", stats.draw_pipeline);
        if (settings_occlusion)
          std::printf("occlusion: %u trees culled, %u leaves and %u triangles saved; GPU pyramid %.2f ms\n",
                      stats.occluded_instances, stats.leaves_saved, stats.triangles_saved, stats.pyramid_ms);
      }
    }
  } catch (...) {
    vk::destroy_context(ctx);
    throw;
  }
  vk::destroy_context(ctx);
  return code;
}

}  // namespace forest::app
