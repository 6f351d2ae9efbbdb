#include "bench/bench_run.h"

#include <algorithm>
#include <cmath>

#include "engine/tools/report/pr_image.h"

namespace forest {

const std::vector<std::string>& bench_mode_names() {
  static const std::vector<std::string> names = {"full", "cook", "opt", "opt-combined", "opt-occl"};
  return names;
}

std::optional<BenchMode> bench_mode(const std::string& name) {
  BenchMode m;
  m.name = name;
  // A prune mode, or opt with a suffix: -combined (models baked with the combined priority),
  // -occl (occlusion feedback).
  std::string base = name;
  if (name == "opt-combined") base = "opt", m.combined_priority = true;
  if (name == "opt-occl") base = "opt", m.occlusion = true;
  std::optional<PruneMode> mode = parse_prune_mode(base);
  if (!mode) return std::nullopt;
  m.prune_mode = *mode;
  return m;
}

std::vector<uint32_t> bench_frames(const CameraPath& path, uint32_t every, uint32_t max_frames) {
  uint32_t last = uint32_t(std::floor(double(path_duration(path)) * double(path.fps) + 1e-6));
  std::vector<uint32_t> frames;
  for (uint32_t f = 0; f <= last; f += std::max(every, 1u)) {
    if (max_frames && frames.size() >= max_frames) break;
    frames.push_back(f);
  }
  return frames;
}

std::vector<BenchFrame> play_bench_path(vk::Context& ctx, const Scene& scene, const CameraPath& path,
                                        const BenchMode& mode, const BenchPlayOptions& options) {
  Renderer renderer(ctx, scene, options.width, options.height, scene.desc.samples);
  std::optional<Renderer> reference;  // full-detail coverage for PR, created on first use
  FrameSettings settings = scene_frame_settings(scene.desc);
  settings.prune_mode = mode.prune_mode;
  settings.occlusion = mode.occlusion;
  settings.shadows = mode.shadows;
  settings.mask = settings.lambda_view = settings.wireframe = false;
  uint64_t terrain_and_sky = scene.terrain.mesh().indices.size() / 3 + 1;  // sky: one full-screen triangle
  uint64_t card_triangles = scene.models.empty() ? 0 : scene.models[0].leaf_card.indices.size() / 3;

  std::map<uint32_t, FrameImage> own_references;  // full-detail coverage per frame, unless the caller shares its own
  std::map<uint32_t, FrameImage>& references = options.references ? *options.references : own_references;
  std::vector<BenchFrame> frames;
  for (size_t i = 0; i < options.frames.size(); ++i) {
    BenchFrame f;
    f.frame = options.frames[i];
    f.time = double(f.frame) / double(path.fps);
    CameraDesc camera = camera_at(path, path.keys.front().time + float(f.time), scene.desc.camera);
    // Occlusion feeds back from the previous frame: with --every k the frames in between
    // (or the last few, --occlusion-warmup) are drawn too, not recorded, else every played
    // frame would be a camera cut.
    uint32_t since = i > 0 ? options.frames[i - 1] + 1 : f.frame;
    if (options.occlusion_warmup)
      since = std::max(i > 0 ? since : 0u, f.frame - std::min(f.frame, *options.occlusion_warmup));
    if (mode.occlusion)
      for (uint32_t g = since; g < f.frame; ++g)
        renderer.render(camera_at(path, path.keys.front().time + float(double(g) / double(path.fps)), scene.desc.camera),
                        nullptr, settings);
    f.stats = renderer.render(camera, nullptr, settings);
    const PipelineStats& ps = f.stats.draw_pipeline;
    f.tree_triangles = ps.available ? (ps.ia_primitives > terrain_and_sky ? ps.ia_primitives - terrain_and_sky : 0)
                                    : f.stats.branch_triangles + uint64_t(f.stats.leaves_drawn) * card_triangles;
    if (options.pr_every && i % options.pr_every == 0) {
      auto [at, missing] = references.try_emplace(f.frame);
      if (missing) {
        if (!reference) reference.emplace(ctx, scene, options.width, options.height, scene.desc.samples);
        FrameSettings full;
        full.mask = true;
        reference->render(camera, &at->second, full);
      }
      const FrameImage& ref_image = at->second;
      FrameSettings test = settings;
      test.mask = true;
      FrameImage test_image;
      renderer.render(camera, &test_image, test);
      f.pr = compare_coverage(ref_image, test_image, nullptr);
      f.has_pr = true;
    }
    frames.push_back(f);
    if (options.progress) options.progress(double(i + 1) / double(options.frames.size()));
  }
  return frames;
}

}  // namespace forest
