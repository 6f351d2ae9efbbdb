// Engine features on the Vulkan device (lavapipe in CI), validation layer on: pipeline
// statistics against the indirect draw counts, the species cache, opt vs cook vs full by
// Precision/Recall, and per-frame CPU cost independent of the instance count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "engine/tools/bake/species_cache.h"
#include "engine/render/renderer.h"
#include "engine/tools/bake/tree_bake.h"
#include "engine/scene/scene.h"
#include "generators/asset/asset_io.h"
#include "generators/asset/pr_tables.h"
#include "generators/species/registry.h"
#include "tests/common/test_files.h"
#include "tests/gpu/gpu_scenes.h"
#include "tests/gpu/validated_gpu_test.h"

using namespace forest;
using namespace forest::test;
namespace fs = std::filesystem;

namespace {

class SceneGpuTest : public ValidatedGpuTest {};

// The common test scene on coarser ground, its preset baked cheaply (one small view).
std::string scene_text(const std::string& extra) {
  return SceneText{.terrain_resolution = 16, .extra = "[bake]\nviews = 1\nresolution = 32\n" + extra}.str();
}

// A scene of `count` copies of one model on flat ground, built without species files.
Scene model_scene(const TreeModel& model, uint32_t count, float radius) {
  SceneDesc desc = parse_scene(scene_text(""));
  desc.species.resize(1);
  desc.terrain.height = 0.0f;
  desc.placement.count = count;
  desc.placement.seed = 21;
  desc.placement.min_spacing = 1.0f;
  desc.placement.radius = radius;
  return scene_of(std::move(desc), {model});
}

// 40 broadleaf trees baked from `views` views at `resolution` px, pruned over 120 m, the
// camera 70 m out looking in.
Scene baked_grove(vk::Context& ctx, uint32_t views, uint32_t resolution) {
  TreeModel m = broadleaf();
  TreeBakeSettings bake;
  bake.impostor = false;  // meshes only: impostors have their own test
  bake.views = views;
  bake.resolution = resolution;
  bake_tree_model(ctx, m, bake);
  Scene s = model_scene(m, 40, 45.0f);
  s.desc.prune_distance = 120.0f;
  s.desc.camera.position = glm::vec3(0.0f, 8.0f, -70.0f);
  s.desc.camera.target = glm::vec3(0.0f, 4.0f, 0.0f);
  return s;
}

}  // namespace

TEST_F(SceneGpuTest, PipelineStatisticsMatchIndirectDrawCounts) {
  ASSERT_TRUE(ctx_.pipeline_statistics) << "lavapipe has pipelineStatisticsQuery; the feature was not enabled";
  TreeModel m = broadleaf();
  Scene s = model_scene(m, 40, 30.0f);
  ASSERT_EQ(s.instances.size(), 40u);
  Renderer r(ctx_, s, 160, 120, 1);
  // A leaf is one triangle around its card quad (engine/render/leaf_card.h), not the quad's two.
  ASSERT_EQ(m.leaf_card.indices.size(), 6u);
  const uint64_t card_triangles = 1;
  for (bool mask : {false, true}) {
    FrameSettings fs;
    fs.mask = mask;
    FrameStats st = r.render(s.desc.camera, nullptr, fs);
    ASSERT_TRUE(st.draw_pipeline.available);
    ASSERT_GT(st.branch_draws, 5u);
    ASSERT_LT(st.branch_draws, 40u) << "want some trees culled";
    // Input assembly saw exactly what the compacted indirect commands asked for: the sky
    // triangle and the terrain (not in mask mode), the bark of every visible tree at its
    // chosen LOD and k leaves per tree, each one point (leaf_card.geom makes its triangle).
    const uint64_t leaves = uint64_t(st.leaves_drawn) * card_triangles;
    // The terrain's chunks in view (terrain_cull.h; this terrain is one chunk).
    EXPECT_EQ(st.terrain_triangles, mask ? 0u : s.terrain.mesh().indices.size() / 3);
    uint64_t expected = uint64_t(st.branch_triangles) + leaves + (mask ? 0 : 1 + st.terrain_triangles);
    EXPECT_EQ(st.draw_pipeline.ia_primitives, expected) << (mask ? "mask" : "shaded");
    EXPECT_EQ(st.draw_pipeline.ia_vertices, 3 * (expected - leaves) + leaves);  // triangle and point lists
    // Every leaf whose size the pruning transition left above zero becomes a triangle.
    EXPECT_LE(st.draw_pipeline.clip_invocations, expected);
    EXPECT_GT(st.draw_pipeline.clip_invocations, expected - leaves);
    EXPECT_GT(st.draw_pipeline.fs_invocations, 0u);
    EXPECT_LE(st.draw_pipeline.clip_primitives, st.draw_pipeline.clip_invocations * 2);
    // One cull thread per instance, rounded up to whole workgroups (not on lavapipe, where
    // a statistics query around a dispatch crashes the driver).
    if (st.cull_pipeline.available) {
      EXPECT_EQ(st.cull_pipeline.cs_invocations, uint64_t((40 + CULL_GROUP_SIZE - 1) / CULL_GROUP_SIZE) * CULL_GROUP_SIZE);
    }
  }
}

TEST_F(SceneGpuTest, SpeciesCacheSecondLoadHitsAndRendersIdentically) {
  fs::path cache = fresh_temp_dir("forest_gpu", "species_cache");
  SceneDesc desc = parse_scene(scene_text("[[tree]]\nspecies = 0\nx = 0\nz = 0\n"));
  desc.prune_mode = PruneMode::opt;  // uses the baked tables
  SpeciesCacheCounts first_counts, second_counts;
  SceneBuildOptions o;
  o.species = cached_species_source({cache, &ctx_, {}}, &first_counts);
  Scene first = build_scene(desc, o);
  EXPECT_EQ(first_counts.misses, 1u);
  EXPECT_EQ(first_counts.hits, 0u);
  ASSERT_TRUE(first.models[0].bake.baked()) << "a preset from the cache must be baked";
  // The entry is the asset and its record (cache_record.h), nothing else: no temporary file.
  std::vector<fs::path> files;
  for (auto& e : fs::directory_iterator(cache)) files.push_back(e.path());
  std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) { return a.extension() < b.extension(); });
  ASSERT_EQ(files.size(), 2u) << "exactly one cached asset and its record, no temporary file left";
  EXPECT_EQ(files[0].extension(), ".glb");
  EXPECT_EQ(files[1].extension(), ".json");
  EXPECT_EQ(files[1].stem(), files[0].stem());
  auto written = fs::last_write_time(files[0]);

  o.species = cached_species_source({cache, &ctx_, {}}, &second_counts);
  Scene second = build_scene(desc, o);
  EXPECT_EQ(second_counts.hits, 1u);
  EXPECT_EQ(second_counts.misses, 0u);
  EXPECT_EQ(fs::last_write_time(files[0]), written) << "a hit must not rewrite the asset";
  EXPECT_EQ(encode_glb(first.models[0]), encode_glb(second.models[0]));
  FrameImage a, b;
  {
    Renderer ra(ctx_, first, desc.width, desc.height, 1);
    ra.render(desc.camera, &a);
  }
  {
    Renderer rb(ctx_, second, desc.width, desc.height, 1);
    rb.render(desc.camera, &b);
  }
  EXPECT_EQ(a.rgba, b.rgba);

  fs::remove_all(cache);
}

TEST_F(SceneGpuTest, OptMatchesCookQualityWithFewerLeaves) {
  // Neubert 2012 §7.2.5: λ_opt(d) is the smallest λ whose PR quality (with s_opt) reaches
  // Cook's quality at d. So on a forest view, opt must reach Cook's Q against the full
  // image while drawing fewer leaves.
  Scene s = baked_grove(ctx_, 1, 64);
  Renderer r(ctx_, s, 160, 120, 1);
  FrameSettings full, cook, opt;
  cook.prune_mode = PruneMode::cook;
  opt.prune_mode = PruneMode::opt;
  r.render_reference(s.desc.camera, full);
  PrResult q_cook = r.compare_with_reference(s.desc.camera, cook);
  PrResult q_opt = r.compare_with_reference(s.desc.camera, opt);
  uint32_t leaves_full = r.render(s.desc.camera, nullptr, full).leaves_drawn;
  uint32_t leaves_cook = r.render(s.desc.camera, nullptr, cook).leaves_drawn;
  uint32_t leaves_opt = r.render(s.desc.camera, nullptr, opt).leaves_drawn;
  std::printf("Q cook %.3f (P %.3f R %.3f, %u leaves), opt %.3f (P %.3f R %.3f, %u leaves), full %u leaves\n",
              q_cook.quality(), q_cook.precision(), q_cook.recall(), leaves_cook, q_opt.quality(), q_opt.precision(),
              q_opt.recall(), leaves_opt, leaves_full);
  EXPECT_LT(leaves_cook, leaves_full);
  EXPECT_LT(leaves_opt, leaves_cook) << "opt should need less geometry than Cook";
  EXPECT_GE(q_opt.quality(), q_cook.quality() - 0.03) << "opt should keep Cook's quality";
  // Cook's quality on this view is ~0.86 (lavapipe: Cook 0.859, opt 0.877 with 19% fewer
  // leaves). An absolute floor too: at Q < 0.8 (about λ = 0.2, s = 1/λ for this model in
  // its bake) whole crowns visibly thin out.
  EXPECT_GE(q_opt.quality(), 0.8);
}

TEST_F(SceneGpuTest, OptKeepsCooksQualityAtEveryResolution) {
  // The run time looks λ_opt up by each tree's projected size as well as d (issue 20), and opt
  // keeps Cook's quality at the same view with 16 × the pixels within the one "equal quality"
  // tolerance, −0.002. (It once also pruned less at the larger size; with each size counted
  // over its sub-pixel phases, the leaves' Q agrees across sizes within a few thousandths (fig2_1:
  // 0.005); what differs with size is the bark's LOD, and the two frames' leaves within 2 %.)
  Scene s = baked_grove(ctx_, 4, 256);
  uint32_t opt_leaves[2] = {0, 0};
  const uint32_t widths[2] = {160, 640};
  for (int k = 0; k < 2; ++k) {
    SCOPED_TRACE(std::to_string(widths[k]) + " px wide");
    Renderer r(ctx_, s, widths[k], widths[k] * 3 / 4, 1);
    FrameSettings full, cook, opt;
    cook.prune_mode = PruneMode::cook;
    opt.prune_mode = PruneMode::opt;
    r.render_reference(s.desc.camera, full);
    PrResult q_cook = r.compare_with_reference(s.desc.camera, cook);
    PrResult q_opt = r.compare_with_reference(s.desc.camera, opt);
    uint32_t leaves_cook = r.render(s.desc.camera, nullptr, cook).leaves_drawn;
    opt_leaves[k] = r.render(s.desc.camera, nullptr, opt).leaves_drawn;
    std::printf("%u x %u: Q cook %.4f (%u leaves), opt %.4f (%u leaves)\n", widths[k], widths[k] * 3 / 4,
                q_cook.quality(), leaves_cook, q_opt.quality(), opt_leaves[k]);
    EXPECT_GE(q_opt.quality(), q_cook.quality() - kEqualQualityTolerance);
    EXPECT_LT(opt_leaves[k], leaves_cook) << "opt should still need less geometry than Cook";
  }
}

TEST_F(SceneGpuTest, CpuFrameTimeIndependentOfInstanceCount) {
  // The frame loop is O(1) in the instances: recording and submitting a frame of 5000 trees
  // costs the CPU about what 100 cost. Loose (< 3x, best of 25 frames, no absolute times:
  // the frame is ~0.05 ms, so one preemption on a busy machine is larger than the effect);
  // the bench (bench/frame_cpu_bench) measures the < 2x of the issue properly (1.16x).
  TreeModel m = broadleaf();
  double best[2] = {1e9, 1e9};
  uint32_t counts[2] = {100, 5000};
  for (int i = 0; i < 2; ++i) {
    Scene s = model_scene(m, counts[i], 400.0f);
    s.desc.terrain.size = 1000.0f;
    s.terrain = make_terrain(s.desc.terrain);
    s.instances = place_trees(s.desc, s.terrain);
    ASSERT_EQ(s.instances.size(), counts[i]);
    // Looking up at the sky: every tree is culled on the GPU, so the GPU part stays cheap;
    // the CPU does the same work either way.
    CameraDesc cam = s.desc.camera;
    cam.target = cam.position + glm::vec3(0.0f, 10.0f, 0.1f);
    Renderer r(ctx_, s, 64, 48, 1);
    for (int f = 0; f < 25; ++f) {
      FrameStats st = r.render(cam, nullptr);
      EXPECT_EQ(st.instances, counts[i]);
      best[i] = std::min(best[i], st.cpu_submit_ms);
    }
  }
  std::printf("CPU per frame: %.3f ms (100 trees), %.3f ms (5000 trees)\n", best[0], best[1]);
  EXPECT_LT(best[1], 3.0 * best[0]);
}
