// `forest bench`: plays a scene's camera path frame by frame in one prune mode and records
// what each frame cost and, at sampled frames, how close its coverage is to full detail.
#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "engine/render/renderer.h"
#include "engine/scene/camera_path.h"

namespace forest {

// full, cook, opt (the scene's baked tables, leaves in the scene's [bake] priority order),
// opt-<order> for every priority order (opt-random, opt-density, opt-orientation,
// opt-combined, opt-layered: opt on models baked with that order; the caller builds that
// scene), opt-occl (opt + depth-buffer occlusion feedback), opt-occl-instanced (opt-occl with
// the leaves drawn as instances of their card instead of by vertex pulling).
// cook-random is Cook et al. as published, whatever the scene's order: random order, s = 1/λ.
struct BenchMode {
  std::string name;
  PruneMode prune_mode = PruneMode::full;
  bool occlusion = false;
  std::string priority;  // the leaf order the models are baked with; empty: the scene's [bake] priority
  bool shadows = false;  // the sun's shadow maps (--shadows); the name then ends in "+shadows"
  bool instanced_leaves = false;  // leaves as card instances, not pulled (opt-occl-instanced)
  bool impostors = false;  // far trees as impostors where their baked Q allows (opt-occl-imp, --impostors on)
};
std::optional<BenchMode> bench_mode(const std::string& name);
const std::vector<std::string>& bench_mode_names();

struct BenchFrame {
  uint32_t frame = 0;
  double time = 0.0;        // seconds along the path
  FrameStats stats;
  uint64_t tree_triangles = 0;  // draw-pass primitives minus terrain and sky
  bool has_pr = false;
  PrResult pr;              // coverage of this frame's trees vs full detail, same camera
  // Per-tree PR at PR frames (BenchPlayOptions::tree_pr): Q of each measured tree drawn alone
  // against its own full-detail mask from this camera, and its projected size (px across
  // its bounding sphere).
  std::vector<float> tree_q, tree_size;
};

struct BenchPlayOptions {
  uint32_t width = 640, height = 360;
  std::vector<uint32_t> frames;  // path frames to play, in order (time = frame / fps)
  uint32_t pr_every = 10;        // PR at every pr_every-th played frame (0: never)
  // At each PR frame, this many trees in view (spread over their projected sizes, at least
  // 4 px across) are also measured one by one, each alone (FrameSettings::solo_instance);
  // 0: none. Not with occlusion (a tree alone has no occluders).
  uint32_t tree_pr = 0;
  // With occlusion: at most this many path frames before each played one are drawn first
  // (unrecorded) so its feedback has a history; none: all frames since the last played one.
  std::optional<uint32_t> occlusion_warmup;
  std::function<void(double)> progress;  // fraction of frames done
  // Full-detail coverage per path frame, kept across the modes that play the same Scene: a
  // reference of forest5000 on lavapipe takes minutes, and it is the same in every mode.
  std::map<uint32_t, FrameImage>* references = nullptr;
  MemoryReport* memory = nullptr;  // when given: the device memory of the mode's renderer
};

// The frames of `path` at its fps from its first to its last key, every `every`-th, at most
// `max_frames` (0: all).
std::vector<uint32_t> bench_frames(const CameraPath& path, uint32_t every, uint32_t max_frames);

// Plays the frames in `mode` on one Renderer (occlusion history carries from frame to frame;
// with occlusion the skipped frames between played ones, or the last `occlusion_warmup` of
// them, are drawn too, unrecorded).
// PR: after a sampled frame, the same renderer draws that camera again as a coverage mask
// with the mode's settings (for opt-occl: with the history the drawn frame left), and a
// second renderer draws the full-detail mask; both are compared on the CPU (pr_image.h).
std::vector<BenchFrame> play_bench_path(vk::Context& ctx, const Scene& scene, const CameraPath& path,
                                        const BenchMode& mode, const BenchPlayOptions& options);

}  // namespace forest
