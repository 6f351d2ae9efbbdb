#include "bench/bench_run.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/trigonometric.hpp>
#include <glm/geometric.hpp>

#include "engine/tools/report/pr_image.h"
#include "prune_math.h"
#include "generators/bake/priority/priority_names.h"

namespace forest {

const std::vector<std::string>& bench_mode_names() {
  static const std::vector<std::string> names = {"full",          "cook",           "cook-random", "opt",
                                                  "opt-random",    "opt-density",    "opt-orientation",
                                                  "opt-combined",  "opt-layered",    "opt-occl",
                                                  "opt-occl-instanced", "opt-occl-imp", "target"};
  return names;
}

std::optional<BenchMode> bench_mode(const std::string& name) {
  BenchMode m;
  m.name = name;
  // A prune mode, or opt with a suffix: -<order> (models baked with that priority order),
  // -occl (occlusion feedback); cook-random: Cook on the random order.
  std::string base = name;
  if (name == "opt-occl") base = "opt", m.occlusion = true;
  if (name == "opt-occl-instanced") base = "opt", m.occlusion = true, m.instanced_leaves = true;
  if (name == "opt-occl-imp") base = "opt", m.occlusion = true, m.impostors = true;
  if (name == "cook-random") base = "cook", m.priority = "random";
  if (name.rfind("opt-", 0) == 0 && parse_priority(name.substr(4))) base = "opt", m.priority = name.substr(4);
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

// Trees whose bounding sphere is in `camera`'s frustum and at least 4 px across, `count` of
// them spread evenly over the sorted projected sizes (all when fewer): (instance, size).
std::vector<std::pair<uint32_t, float>> trees_in_view(const Scene& scene, const CameraDesc& camera, uint32_t width,
                                                      uint32_t height, uint32_t count) {
  CameraMatrices cm = camera_matrices(camera, float(width) / float(height));
  const float pixels_per_meter = 0.5f * float(height) / std::tan(0.5f * glm::radians(camera.fov_deg));
  std::vector<std::pair<float, uint32_t>> seen;  // (size, instance)
  for (uint32_t i = 0; i < scene.instances.size(); ++i) {
    const gpu::Instance& inst = scene.instances[i];
    const glm::vec4 bs = scene.models[inst.model].bounding_sphere;
    const glm::vec2 cs = inst.yaw_cos_sin;
    glm::vec3 c(cs.x * bs.x + cs.y * bs.z, bs.y, -cs.y * bs.x + cs.x * bs.z);
    c = glm::vec3(inst.position_scale) + c * inst.position_scale.w;
    const float r = bs.w * inst.position_scale.w;
    bool inside = true;
    for (const glm::vec4& p : cm.frustum) inside = inside && glm::dot(glm::vec3(p), c) + p.w >= -r;
    float size = prune::projected_size(r, glm::distance(c, cm.position), pixels_per_meter);
    if (inside && size >= 4.0f) seen.push_back({std::min(size, 1e5f), i});
  }
  std::sort(seen.begin(), seen.end());
  std::vector<std::pair<uint32_t, float>> out;
  const size_t n = std::min<size_t>(count, seen.size());
  for (size_t k = 0; k < n; ++k) {
    const auto& [size, i] = seen[n > 1 ? k * (seen.size() - 1) / (n - 1) : 0];
    out.push_back({i, size});
  }
  return out;
}

std::vector<BenchFrame> play_bench_path(vk::Context& ctx, const Scene& scene, const CameraPath& path,
                                        const BenchMode& mode, const BenchPlayOptions& options) {
  Renderer renderer(ctx, scene, options.width, options.height, scene.desc.samples);
  if (options.memory) *options.memory = renderer.memory();
  std::optional<Renderer> reference;  // full-detail coverage for PR, created on first use
  FrameSettings settings = scene_frame_settings(scene.desc);
  settings.prune_mode = mode.prune_mode;
  settings.occlusion = mode.occlusion;
  settings.instanced_leaves = mode.instanced_leaves;
  settings.shadows = mode.shadows;
  settings.impostors = mode.impostors ? ImpostorMode::switched : ImpostorMode::off;
  settings.mask = settings.lambda_view = settings.wireframe = false;
  uint64_t card_triangles = scene.models.empty() ? 0 : scene.models[0].leaf_card.indices.size() / 3;

  std::map<uint32_t, FrameImage> own_references;  // full-detail coverage per frame, unless the caller shares its own
  std::map<uint32_t, FrameImage>& references = options.references ? *options.references : own_references;
  auto camera_at_frame = [&](uint32_t frame) {
    return camera_at(path, path.keys.front().time + float(double(frame) / double(path.fps)), scene.desc.camera);
  };
  // One unrecorded warm-up draw: a renderer's first draw pays for what lavapipe compiles on
  // first use (its shader variants), which made each mode's frame 0 its slowest (bench_grove:
  // Cook's 248 ms against 85-114 ms for its other frames; 36 ms with the warm-up). The first
  // recorded draw is then flagged a camera cut, so occlusion starts from no history, as it
  // did without the warm-up.
  if (!options.frames.empty()) renderer.render(camera_at_frame(options.frames.front()), nullptr, settings);
  bool first_draw = true;
  auto draw = [&](const CameraDesc& camera) {
    FrameSettings s = settings;
    s.camera_cut = std::exchange(first_draw, false);
    return renderer.render(camera, nullptr, s);
  };
  std::vector<BenchFrame> frames;
  for (size_t i = 0; i < options.frames.size(); ++i) {
    BenchFrame f;
    f.frame = options.frames[i];
    f.time = double(f.frame) / double(path.fps);
    CameraDesc camera = camera_at_frame(f.frame);
    // Occlusion feeds back from the previous frame: with --every k the frames in between
    // (or the last few, --occlusion-warmup) are drawn too, not recorded, else every played
    // frame would be a camera cut.
    uint32_t since = i > 0 ? options.frames[i - 1] + 1 : f.frame;
    if (options.occlusion_warmup)
      since = std::max(i > 0 ? since : 0u, f.frame - std::min(f.frame, *options.occlusion_warmup));
    if (mode.occlusion)
      for (uint32_t g = since; g < f.frame; ++g) draw(camera_at_frame(g));
    f.stats = draw(camera);
    const PipelineStats& ps = f.stats.draw_pipeline;
    const uint64_t terrain_and_sky = uint64_t(f.stats.terrain_triangles) + 1;  // sky: one full-screen triangle
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
      if (options.tree_pr && !mode.occlusion && !reference) reference.emplace(ctx, scene, options.width, options.height, scene.desc.samples);
      if (options.tree_pr && !mode.occlusion)
        for (auto [tree, size] : trees_in_view(scene, camera, options.width, options.height, options.tree_pr)) {
          FrameSettings full_alone, test_alone = test;
          full_alone.mask = true;
          full_alone.solo_instance = test_alone.solo_instance = tree;
          FrameImage ref_alone, test_alone_image;
          reference->render(camera, &ref_alone, full_alone);
          renderer.render(camera, &test_alone_image, test_alone);
          f.tree_q.push_back(float(compare_coverage(ref_alone, test_alone_image, nullptr).quality()));
          f.tree_size.push_back(size);
        }
    }
    frames.push_back(f);
    if (options.progress) options.progress(double(i + 1) / double(options.frames.size()));
  }
  return frames;
}

}  // namespace forest
