// Hardening on the GPU: synchronization validation over full pruned frames, reproducible
// per-frame leaf counts, and GPU allocations beyond the device's limits reported as errors.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "engine/render/renderer.h"
#include "engine/scene/scene.h"
#include "generators/asset/pr_tables.h"
#include "generators/species/registry.h"
#include "tests/gpu/gpu_scenes.h"
#include "tests/gpu/validated_gpu_test.h"

using namespace forest;
using namespace forest::test;

namespace {

// 120 broadleaf trees on hills, seen from the side so that distances (and λ) vary.
const std::string kScene =
    SceneText{.samples = 4,
              .render = "mode = \"opt\"\nprune_distance = 120\n",
              .position = {0.0f, 12.0f, -70.0f},
              .target = {0.0f, 3.0f, 0.0f},
              .terrain_height = 4.0f,
              .extra = "[placement]\ncount = 120\nseed = 5\nmin_spacing = 3\nradius = 60\n"}
        .str();

// Pruning tables that keep λ = 1 − d and grow leaves as they drop (s = 1/λ, capped).
PrTables ramp_tables() {
  PrSizeTables t;
  for (int i = 0; i < S_SAMPLES; ++i) {
    float l = float(i) / float(S_SAMPLES - 1);
    t.s_opt.push_back(l > 0.1f ? 1.0f / l : 10.0f);
    t.q_opt.push_back(1.0f);
    t.q_inverse.push_back(1.0f);
  }
  for (int i = 0; i < D_SAMPLES; ++i) {
    float d = float(i) / float(D_SAMPLES - 1);
    t.lambda_opt.push_back(1.0f - d);
  }
  t.s_far.assign(F_SAMPLES, 10.0f);
  t.q_far.assign(F_SAMPLES, 1.0f);
  t.q_inverse_far.assign(F_SAMPLES, 1.0f);
  t.q_low.assign(S_SAMPLES, 1.0f);
  t.q_low_far.assign(F_SAMPLES, 1.0f);
  return pr_tables_at_every_size(t);
}

Scene pruned_scene() {
  SceneDesc desc = parse_scene(kScene, "hardening.toml");
  Scene scene = build_scene(desc);
  scene.models[0].bake.pr_tables = ramp_tables();
  return scene;
}

// A short camera path: the same frames every run.
std::vector<CameraDesc> camera_path(const SceneDesc& desc) {
  std::vector<CameraDesc> path;
  for (int i = 0; i < 3; ++i) {
    CameraDesc c = desc.camera;
    c.position.z += 15.0f * float(i);
    c.position.x += 6.0f * float(i);
    path.push_back(c);
  }
  return path;
}

std::vector<uint32_t> leaves_per_frame(vk::Context& ctx, const Scene& scene, FrameImage* last) {
  Renderer renderer(ctx, scene, scene.desc.width, scene.desc.height, scene.desc.samples);
  std::vector<uint32_t> counts;
  for (const CameraDesc& c : camera_path(scene.desc))
    counts.push_back(renderer.render(c, last, scene_frame_settings(scene.desc)).leaves_drawn);
  // Then occlusion feedback at the last view: depth pyramid, cull with the hull samples and
  // the per-leaf test of partly hidden trees (tail_cull.comp), drawn from its index list.
  FrameSettings occlusion = scene_frame_settings(scene.desc);
  occlusion.occlusion = true;
  for (int f = 0; f < 3; ++f) {
    FrameStats stats = renderer.render(camera_path(scene.desc).back(), last, occlusion);
    counts.push_back(stats.leaves_drawn);
    counts.push_back(stats.leaves_saved);
  }
  return counts;
}

}  // namespace

TEST(GpuHardening, FullPrunedFramesPassSynchronizationValidation) {
  vk::Context ctx;
  vk::create_context(ctx, validation_options(/*synchronization=*/true));
  {
    Scene scene = pruned_scene();
    FrameImage image;
    std::vector<uint32_t> first = leaves_per_frame(ctx, scene, &image);
    // Pruning is on: farther frames and trees draw fewer leaves than the full models have.
    uint64_t all = uint64_t(scene.models[0].leaves.size()) * scene.instances.size();
    for (size_t i = 0; i < 3; ++i) {
      EXPECT_GT(first[i], 0u);
      EXPECT_LT(first[i], all);
    }
    EXPECT_EQ(first[4], 0u) << "the first occlusion frame saves nothing";
    EXPECT_GT(first.back(), 0u) << "occlusion saved no leaf: the passes under test did not run";
    // A second run over the same path (a fresh renderer) draws the same leaves per frame.
    EXPECT_EQ(leaves_per_frame(ctx, scene, nullptr), first);
  }
  destroy_validated_context(ctx);
}

TEST(GpuHardening, BufferBeyondTheDeviceIsReportedNotCrashed) {
  vk::Context ctx;
  vk::create_context(ctx, validation_options());
  try {
    vk::Buffer b = vk::create_buffer(ctx, VkDeviceSize(1) << 52, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                     vk::MemoryUse::device);
    vk::destroy_buffer(ctx, b);
    ADD_FAILURE() << "a 4 PiB buffer was created";
  } catch (const vk::VkFailure& e) {
    EXPECT_NE(std::string(e.what()).find("out of GPU memory"), std::string::npos) << e.what();
  }
  destroy_validated_context(ctx);
}

TEST(GpuHardening, SynchronizationValidationIsReallyOn) {
  // Two writes to one buffer without a barrier between them: a write-after-write hazard that
  // only synchronization validation reports. Proves the test above checks something.
  vk::Context ctx;
  vk::create_context(ctx, validation_options(/*synchronization=*/true));
  vk::Buffer b = vk::create_buffer(ctx, 256, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::device);
  vk::submit_now(ctx, [&](VkCommandBuffer cmd) {
    vkCmdFillBuffer(cmd, b.buffer, 0, 256, 1u);
    vkCmdFillBuffer(cmd, b.buffer, 0, 256, 2u);
  });
  vk::destroy_buffer(ctx, b);
  vk::destroy_context(ctx);
  EXPECT_GT(ctx.validation_messages.load(), 0u);
  EXPECT_NE(ctx.last_validation_message.find("WRITE_AFTER_WRITE"), std::string::npos) << ctx.last_validation_message;
}
