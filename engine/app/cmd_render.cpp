#include <chrono>
#include <cmath>
#include <cstdio>

#include "engine/app/app_common.h"
#include "engine/app/commands.h"
#include "engine/app/progress.h"
#include "engine/present/image_io.h"
#include "engine/render/renderer.h"
#include "engine/scene/camera_path.h"
#include "engine/scene/scene.h"
#include "generators/core/input_error.h"

namespace forest::app {

namespace {

using clock = std::chrono::steady_clock;

// When each stage of a render ended, for --stats.
struct RenderTimes {
  clock::time_point start, scene, upload, done;
};

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

// --width, --height, --mode, --quality, --view, --sun and --exposure over the scene file's settings.
void override_render_settings(SceneDesc& desc, const RenderArgs& args) {
  override_size(desc, args.width, args.height);
  if (args.sun) {  // azimuth from +x toward +z, elevation above the horizon, degrees
    float az = glm::radians(args.sun->x), el = glm::radians(args.sun->y);
    desc.sky.sun_direction = {std::cos(el) * std::cos(az), std::sin(el), std::cos(el) * std::sin(az)};
  }
  if (args.exposure) desc.exposure = *args.exposure;
  if (!args.mode.empty())
    desc.prune_mode = *parse_prune_mode(args.mode);  // CLI11 checked it against prune_mode_names()
  if (args.quality) desc.quality = *args.quality;
  if (!args.view.empty()) {
    desc.lambda_view = args.view == "lambda";
    desc.mask_view = args.view == "mask";
  }
}

// The scene's camera, or the camera of --path at --frame / --time (which need --path).
CameraDesc render_camera(const SceneDesc& desc, const RenderArgs& args) {
  if (!args.path.empty()) {
    const CameraPath* path = find_path(desc, args.path);
    if (!path) throw InputError(args.scene, 0, "--path", "no [[path]] named '" + args.path + "'");
    double t = args.time ? *args.time : args.frame ? double(*args.frame) / path->fps : 0.0;
    return camera_at(*path, path->keys.front().time + float(t), desc.camera);
  }
  if (args.frame || args.time) throw InputError(args.scene, 0, args.frame ? "--frame" : "--time", "needs --path NAME");
  return desc.camera;
}

// One still frame into `image`; the renderer lives only as long as the frame, so its GPU
// memory is gone before the image is written.
FrameStats render_still(vk::Context& ctx, const Scene& scene, const SceneDesc& desc, const RenderArgs& args,
                        const CameraDesc& camera, FrameImage& image, RenderTimes& times) {
  Renderer renderer(ctx, scene, desc.width, desc.height, desc.samples);
  times.upload = clock::now();
  FrameSettings settings = scene_frame_settings(desc);
  if (args.occlusion) settings.occlusion = *args.occlusion;
  if (args.shadows) settings.shadows = *args.shadows;
  if (args.impostors) settings.impostors = *args.impostors ? ImpostorMode::switched : ImpostorMode::off;
  settings.pyramid_overlay = args.overlay == "pyramid";
  // Occlusion feeds back from one frame to the next: a still picture shows the steady
  // state, after the hidden trees have thinned out (kWarmupFrames from the same camera).
  constexpr int kWarmupFrames = 5;
  const int frames = settings.occlusion ? kWarmupFrames + 1 : 1;
  // A forest frame on lavapipe takes seconds: a bar over the frames (terminals only).
  ProgressBar bar("render");
  bar.update(0.0);
  for (int i = 0; i + 1 < frames; ++i) {
    renderer.render(camera, nullptr, settings);
    bar.update(double(i + 1) / frames);
  }
  FrameStats stats = renderer.render(camera, &image, settings);
  bar.update(1.0);
  return stats;
}

// --stats: where the time went, what was drawn against the full-detail size, and the GPU's
// pipeline statistics.
void print_render_stats(const FrameStats& stats, const Scene& scene, const RenderTimes& t, bool occlusion) {
  auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
  std::printf("time: scene %.0f ms (generate + place), upload %.0f ms, frame %.1f ms wall; "
              "GPU cull %.2f ms, draw %.1f ms, frame %.1f ms\n",
              ms(t.start, t.scene), ms(t.scene, t.upload), ms(t.upload, t.done), stats.cull_ms, stats.draw_ms,
              stats.frame_ms);
  std::printf("branches: %u triangles drawn; trees per LOD:", stats.branch_triangles);
  for (uint32_t n : stats.lod_draws) std::printf(" %u", n);
  std::printf("; mean lambda %.3f\n", stats.mean_lambda);
  FullDetailSize full = full_detail_size(scene);
  std::printf("instances visible %u of %u; leaves drawn %u; full detail: %llu triangles, %llu vertices "
              "(%.2f B as input assembly counts them, 3 per triangle)\n",
              stats.branch_draws, stats.instances, stats.leaves_drawn, (unsigned long long)full.triangles,
              (unsigned long long)full.vertices, 3e-9 * double(full.triangles));
  std::printf("CPU per frame (constants + record + submit): %.3f ms\n", stats.cpu_submit_ms);
  print_pipeline_stats("cull", stats.cull_pipeline);
  print_pipeline_stats("draw", stats.draw_pipeline);
  if (occlusion)
    std::printf("occlusion: %u trees culled, %u leaves and %u triangles saved; GPU pyramid %.2f ms\n",
                stats.occluded_instances, stats.leaves_saved, stats.triangles_saved, stats.pyramid_ms);
  if (stats.shadow_ms > 0.0) {
    std::printf("shadows: GPU %.1f ms (%.1f %% of the frame); casters per cascade", stats.shadow_ms,
                stats.frame_ms > 0.0 ? 100.0 * stats.shadow_ms / stats.frame_ms : 0.0);
    for (int c = 0; c < SHADOW_CASCADES; ++c)
      std::printf(" %u (%u triangles)", stats.shadow_casters[c], stats.shadow_triangles[c]);
    std::printf("\n");
  }
}

}  // namespace

int run_render(const RenderArgs& args) {
  RenderTimes times;
  times.start = clock::now();
  std::filesystem::path out = args.out;
  check_output_path(out, "--out");
  SceneDesc desc = load_scene_file(args.scene);
  override_render_settings(desc, args);
  if (args.overlay == "pyramid" && !args.occlusion.value_or(desc.occlusion))
    throw InputError(args.scene, 0, "--overlay", "pyramid needs occlusion on ([render] occlusion or --occlusion on)");
  CameraDesc camera = render_camera(desc, args);
  Scene scene = build_cached_scene(desc, args.scene, args.cache);
  times.scene = clock::now();

  CommandContext context(context_options(args.device, args.validate));
  vk::Context& ctx = context.ctx;
  FrameImage image;
  bool settings_occlusion = args.occlusion.value_or(desc.occlusion);
  times.upload = clock::now();
  FrameStats stats = render_still(ctx, scene, desc, args, camera, image, times);
  times.done = clock::now();
  if (validation_failed(ctx, "image")) return 1;
  write_image(image, out);
  std::printf("wrote %s (%ux%u) on %s: %u trees, %u visible, %u leaves drawn\n", out.c_str(), desc.width,
              desc.height, ctx.properties.deviceName, stats.instances, stats.branch_draws, stats.leaves_drawn);
  if (args.stats) print_render_stats(stats, scene, times, settings_occlusion);
  return 0;
}

}  // namespace forest::app
