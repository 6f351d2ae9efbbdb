// Depth-buffer occlusion feedback (Neubert 2012 §7.4) on the Vulkan device (lavapipe in CI),
// validation layer on: the depth pyramid's contents, Fig 7.13 (a tree hidden behind a row
// is pruned, its visible neighbours are not), hidden pruning that does not show, camera cuts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>

#include "engine/occlusion/depth_pyramid.h"
#include "engine/tools/report/pr_image.h"
#include "engine/render/renderer.h"
#include "generators/bake/hull/hull.h"
#include "generators/species/registry.h"
#include "tests/gpu/gpu_scenes.h"
#include "tests/gpu/validated_gpu_test.h"

using namespace forest;
using namespace forest::test;

namespace {

class OcclusionTest : public ValidatedGpuTest {};

// The broadleaf preset with its metaball hull attached (the hull samples a bake writes).
const TreeModel& broadleaf_with_hull() {
  static const TreeModel model = [] {
    TreeModel m = broadleaf();
    attach_hull(m, build_hull(m.leaves, plant_height(m)));
    return m;
  }();
  return model;
}

// The same tree with leaves twice as long: a dense crown that hides what is behind it.
TreeModel dense(TreeModel m) {
  for (LeafPlacement& l : m.leaves) l.scale *= 2.0f;
  return m;
}

// Flat ground, no fog, hand-placed trees of `models`.
Scene make_scene(std::vector<TreeModel> models, std::vector<TreeDesc> trees) {
  SceneDesc desc = flat_ground(160, 120, 200.0f);
  desc.trees = std::move(trees);
  desc.camera.position = {0.0f, 6.7f, -20.0f};
  desc.camera.target = {0.0f, 6.7f, 0.0f};
  desc.camera.fov_deg = 45.0f;
  return scene_of(std::move(desc), std::move(models));
}

// Fig 7.13: a row of three dense trees (model 0) across the view, crowns side by side, one
// more behind the middle one, and a tree (model 1) straight behind those two, far enough to
// hide in their crowns: the last instance. The camera looks at the crowns' height.
std::vector<TreeDesc> row_and_hidden_tree() {
  return {{0, -6.5f, 0.0f, 1.0f, 0.0f}, {0, 0.0f, 0.0f, 1.0f, 50.0f}, {0, 6.5f, 0.0f, 1.0f, 100.0f},
          {0, 0.5f, 4.0f, 1.0f, 170.0f}, {1, 0.0f, 30.0f, 1.0f, 0.0f}};
}

size_t differing_pixels(const FrameImage& a, const FrameImage& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.rgba.size(); i += 4) n += std::memcmp(&a.rgba[i], &b.rgba[i], 3) != 0;
  return n;
}

}  // namespace

// Every pyramid texel is the farthest (minimum, reversed Z) depth of the pixels under it,
// with the MIN-reduction sampler and with the 4-tap fallback.
TEST_F(OcclusionTest, PyramidHoldsTheFarthestDepthOfItsFootprint) {
  const uint32_t w = 100, h = 60;
  std::vector<float> depth(size_t(w) * h);
  uint32_t x = 12345;
  for (float& d : depth) {  // xorshift: values spread over (0, 1)
    x ^= x << 13, x ^= x >> 17, x ^= x << 5;
    d = float(x % 100000) / 100000.0f + 1e-5f;
  }
  vk::Image image = vk::create_image(ctx_, {w, h}, VK_FORMAT_D32_SFLOAT,
                                     VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                                     VK_IMAGE_ASPECT_DEPTH_BIT);
  vk::Buffer staging = vk::create_buffer(ctx_, depth.size() * 4, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, vk::MemoryUse::upload);
  std::memcpy(staging.mapped, depth.data(), depth.size() * 4);

  // CPU reference: level 0 = min over the pixels each texel overlaps, then 2x2 minima.
  std::vector<std::vector<float>> expected(1, std::vector<float>(64 * 32));
  for (uint32_t ty = 0; ty < 32; ++ty)
    for (uint32_t tx = 0; tx < 64; ++tx) {
      float m = 1.0f;
      for (uint32_t py = ty * h / 32; py < std::min((ty + 1) * h / 32 + ((ty + 1) * h % 32 != 0), h); ++py)
        for (uint32_t px = tx * w / 64; px < std::min((tx + 1) * w / 64 + ((tx + 1) * w % 64 != 0), w); ++px)
          m = std::min(m, depth[py * w + px]);
      expected[0][ty * 64 + tx] = m;
    }
  for (uint32_t lw = 64, lh = 32; lw > 1 || lh > 1;) {
    uint32_t nw = std::max(lw / 2, 1u), nh = std::max(lh / 2, 1u);
    const std::vector<float>& up = expected.back();
    std::vector<float> next(size_t(nw) * nh);
    for (uint32_t ty = 0; ty < nh; ++ty)
      for (uint32_t tx = 0; tx < nw; ++tx) {
        float m = 1.0f;
        for (uint32_t dy = 0; dy < 2; ++dy)
          for (uint32_t dx = 0; dx < 2; ++dx)
            m = std::min(m, up[std::min(ty * 2 + dy, lh - 1) * lw + std::min(tx * 2 + dx, lw - 1)]);
        next[ty * nw + tx] = m;
      }
    expected.push_back(std::move(next));
    lw = nw, lh = nh;
  }

  for (bool minmax : {true, false}) {
    SCOPED_TRACE(minmax ? "MIN-reduction sampler" : "4-tap fallback");
    DepthPyramid p = create_depth_pyramid(ctx_, image.view, {w, h}, minmax);
    EXPECT_EQ(p.minmax_sampler, minmax && supports_minmax_reduction(ctx_));
    ASSERT_EQ(p.size.width, 64u);
    ASSERT_EQ(p.size.height, 32u);
    ASSERT_EQ(p.levels, 7u);
    vk::submit_now(ctx_, [&](VkCommandBuffer cmd) {
      vk::image_barrier(cmd, image.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                        VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, 0,
                        VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
      VkBufferImageCopy region{};
      region.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
      region.imageExtent = {w, h, 1};
      vkCmdCopyBufferToImage(cmd, staging.buffer, image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
      vk::image_barrier(cmd, image.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                        VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                        VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
      record_depth_pyramid(cmd, p);
    });
    std::vector<std::vector<float>> levels = read_depth_pyramid(ctx_, p);
    ASSERT_EQ(levels.size(), expected.size());
    for (size_t l = 0; l < levels.size(); ++l) EXPECT_EQ(levels[l], expected[l]) << "level " << l;
    destroy_depth_pyramid(ctx_, p);
  }
  vk::destroy_buffer(ctx_, staging);
  vk::destroy_image(ctx_, image);
}

// Fig 7.13: the tree behind the row thins to λ <= 0.15 λ(d) within a few frames; the row,
// in plain view, keeps full detail. Leaves are what hides it: behind a leafless row the
// same tree keeps its detail.
TEST_F(OcclusionTest, TreeHiddenBehindARowIsPruned) {
  const TreeModel& m = broadleaf_with_hull();
  Scene s = make_scene({dense(m), m}, row_and_hidden_tree());
  const uint32_t hidden = uint32_t(s.instances.size()) - 1;
  Renderer r(ctx_, s, 160, 120, 1);
  FrameSettings occl;
  occl.occlusion = true;
  FrameStats first = r.render(s.desc.camera, nullptr, occl);
  EXPECT_TRUE(first.camera_cut) << "the first frame has no previous depth";
  EXPECT_EQ(first.leaves_saved, 0u);
  int frames_to_prune = 0;
  FrameStats last;
  for (int f = 1; f <= 6 && frames_to_prune == 0; ++f) {
    last = r.render(s.desc.camera, nullptr, occl);
    EXPECT_FALSE(last.camera_cut);
    if (r.instance_states()[hidden].occlusion <= 0.15f) frames_to_prune = f;
  }
  EXPECT_GT(frames_to_prune, 0) << "hidden tree still at " << r.instance_states()[hidden].occlusion;
  EXPECT_LE(frames_to_prune, 5);
  std::vector<gpu::InstanceState> st = r.instance_states();
  // 0.15, not 0.1: since the leaf mips keep the alpha-tested coverage (leaf_textures.cpp), the
  // row's distant leaves no longer grow into solid cards, and one of the hull samples of the
  // hidden tree (0.111) sees through a gap.
  EXPECT_LE(st[hidden].visible, 0.15f);
  for (uint32_t i = 0; i < 3; ++i) EXPECT_GE(st[i].occlusion, 0.85f) << "front-row tree " << i;  // a dense crown hides its own far-side samples
  EXPECT_GT(last.leaves_saved, uint32_t(m.leaves.size()) * 8 / 10);
  EXPECT_LT(last.leaves_drawn, first.leaves_drawn);
  EXPECT_EQ(last.leaves_drawn + last.leaves_saved, first.leaves_drawn);

  TreeModel leafless = dense(m);
  leafless.leaves.clear();
  Scene bare = make_scene({leafless, m}, row_and_hidden_tree());
  Renderer rb(ctx_, bare, 160, 120, 1);
  for (int f = 0; f < 4; ++f) rb.render(bare.desc.camera, nullptr, occl);
  EXPECT_GE(rb.instance_states()[hidden].occlusion, 0.5f) << "trunks alone hide the tree";
}

// The scene of Fig 7.13 with two more trees deep behind the row and one off to the side in
// plain view.
Scene hidden_pruning_scene(const TreeModel& m) {
  Scene s = make_scene({dense(m), m}, row_and_hidden_tree());
  s.desc.trees.push_back({1, -1.0f, 45.0f, 1.0f, 60.0f});
  s.desc.trees.push_back({1, 1.5f, 60.0f, 1.0f, 120.0f});
  s.desc.trees.push_back({1, -14.0f, 20.0f, 1.0f, 30.0f});
  s.instances = place_trees(s.desc, s.terrain);
  return s;
}

// The picture with occlusion feedback is the picture without it, as far as Precision/Recall
// of the tree coverage can tell (Q >= 0.99), though it draws fewer leaves. The hidden trees
// show through gaps in the row: Neubert 2012 §7.4's prefix of λ·o alone loses those leaves (Q was 0.9879);
// tail_cull.comp keeps every leaf of the rest of the prefix that the previous frame saw.
TEST_F(OcclusionTest, HiddenPruningIsNotVisible) {
  Scene s = hidden_pruning_scene(broadleaf_with_hull());
  Renderer r(ctx_, s, 160, 120, 1);
  FrameSettings plain, occl;
  occl.occlusion = true;
  r.render_reference(s.desc.camera, plain);
  FrameStats without = r.render(s.desc.camera, nullptr, plain), with;
  for (int f = 0; f < 5; ++f) with = r.render(s.desc.camera, nullptr, occl);
  EXPECT_LT(with.leaves_drawn, without.leaves_drawn * 9 / 10) << "occlusion saved too little to matter";
  EXPECT_EQ(with.leaves_drawn + with.leaves_saved, without.leaves_drawn);
  PrResult pr = r.compare_with_reference(s.desc.camera, occl);
  EXPECT_GE(pr.quality(), 0.99) << "P " << pr.precision() << " R " << pr.recall();
}

// The same while the camera slides sideways (0.1 m per frame, Cook's λ): every frame with
// occlusion feedback against the same frame without, though what the previous frame saw is
// a step behind.
TEST_F(OcclusionTest, HiddenPruningStaysInvisibleWhileTheCameraMoves) {
  Scene s = hidden_pruning_scene(broadleaf_with_hull());
  Renderer plain_renderer(ctx_, s, 160, 120, 1), occl_renderer(ctx_, s, 160, 120, 1);
  FrameSettings plain, occl;
  plain.mask = occl.mask = true;
  plain.prune_mode = occl.prune_mode = PruneMode::cook;
  occl.occlusion = true;
  uint64_t drawn = 0, drawn_without = 0;
  double worst_q = 1.0;
  for (int step = 0; step < 16; ++step) {
    CameraDesc camera = s.desc.camera;
    camera.position.x += 0.1f * float(step);
    camera.target.x += 0.1f * float(step);
    FrameImage reference, test;
    FrameStats without = plain_renderer.render(camera, &reference, plain);
    FrameStats with = occl_renderer.render(camera, &test, occl);
    EXPECT_EQ(with.camera_cut, step == 0);
    if (step < 4) continue;  // the hidden trees thin out over the first frames
    worst_q = std::min(worst_q, compare_coverage(reference, test, nullptr).quality());
    drawn += with.leaves_drawn;
    drawn_without += without.leaves_drawn;
  }
  EXPECT_GE(worst_q, 0.99);
  EXPECT_LT(drawn, drawn_without * 9 / 10) << "occlusion saved too little to matter";
}

// After a camera cut every tree counts as visible: the first frame of the new view is
// exactly the frame drawn without occlusion, whether the cut is flagged or detected.
TEST_F(OcclusionTest, CameraCutNeverShowsAHole) {
  const TreeModel& m = broadleaf_with_hull();
  Scene s = make_scene({dense(m), m}, row_and_hidden_tree());
  Renderer r(ctx_, s, 160, 120, 1);
  FrameSettings plain, occl;
  occl.occlusion = true;
  auto converge = [&] {
    for (int f = 0; f < 5; ++f) r.render(s.desc.camera, nullptr, occl);
    ASSERT_LE(r.instance_states().back().occlusion, 0.15f);
  };
  // Detected: the camera jumps behind the forest, where the pruned tree is in front.
  CameraDesc behind = s.desc.camera;
  behind.position = {0.0f, 4.0f, 36.0f};
  behind.target = {0.0f, 4.0f, 0.0f};
  converge();
  FrameImage cut_image, reference;
  FrameStats cut = r.render(behind, &cut_image, occl);
  EXPECT_TRUE(cut.camera_cut);
  EXPECT_EQ(cut.leaves_saved, 0u);
  r.render(behind, &reference, plain);
  EXPECT_EQ(differing_pixels(cut_image, reference), 0u);

  // Flagged: a step too small to be detected, declared a cut by the caller.
  CameraDesc step = s.desc.camera;
  step.position.x += 0.5f;
  step.target.x += 0.5f;
  converge();
  FrameSettings flagged = occl;
  flagged.camera_cut = true;
  FrameImage flagged_image;
  EXPECT_TRUE(r.render(step, &flagged_image, flagged).camera_cut);
  r.render(step, &reference, plain);
  EXPECT_EQ(differing_pixels(flagged_image, reference), 0u);
  // The same small step unflagged is coherent motion: the hidden tree stays pruned.
  converge();
  FrameStats moved = r.render(step, nullptr, occl);
  EXPECT_FALSE(moved.camera_cut);
  EXPECT_GT(moved.leaves_saved, 0u);
}

// tail_cull.comp's lists, read back: each job's kept leaves are distinct leaves of the range
// it tested, in priority order, as many as its draw counts. The scene has a tree half behind
// the row, whose tail is long and half seen, so a round's kept leaves come from several
// threads, subgroups and rounds (32 consecutive leaves a thread): a leaf placed by a wrong prefix sum
// overwrites another or leaves a gap, and the list is no longer increasing.
TEST_F(OcclusionTest, TailListsKeepThePriorityOrder) {
  Scene s = hidden_pruning_scene(broadleaf_with_hull());
  s.desc.trees.push_back({1, 9.5f, 14.0f, 1.0f, 10.0f});  // half behind the row's right-hand tree
  s.instances = place_trees(s.desc, s.terrain);
  for (bool instanced : {false, true}) {
    Renderer r(ctx_, s, 160, 120, 1);
    FrameSettings occl;
    occl.occlusion = true;
    occl.instanced_leaves = instanced;
    FrameStats stats;
    for (int f = 0; f < 5; ++f) stats = r.render(s.desc.camera, nullptr, occl);
    std::vector<Renderer::TailList> lists = r.tail_lists(instanced);
    ASSERT_FALSE(lists.empty());
    uint64_t dropped = 0, misplaced = 0;
    uint32_t most_kept = 0;
    std::string first_misplaced;
    for (const Renderer::TailList& t : lists) {
      EXPECT_EQ(t.leaf_list, uint32_t(LEAF_LIST_TAIL));
      ASSERT_EQ(t.leaves.size(), t.kept);
      for (size_t i = 0; i < t.leaves.size(); ++i) {
        bool in_range = t.leaves[i] >= t.job.first_leaf && t.leaves[i] < t.job.end_leaf;
        bool after_previous = i == 0 || t.leaves[i] > t.leaves[i - 1];
        if (in_range && after_previous) continue;
        if (misplaced++ == 0)
          first_misplaced = "entry " + std::to_string(i) + " (leaf " + std::to_string(t.leaves[i]) + ") of the job over leaves [" +
                            std::to_string(t.job.first_leaf) + ", " + std::to_string(t.job.end_leaf) + ")";
      }
      dropped += t.job.end_leaf - t.job.first_leaf - t.kept;
      most_kept = std::max(most_kept, t.kept);
    }
    EXPECT_EQ(misplaced, 0u) << "first: " << first_misplaced;
    // Every saved leaf is a tail leaf that was dropped: no tree here is hidden whole.
    EXPECT_EQ(stats.occluded_instances, 0u);
    EXPECT_EQ(dropped, stats.leaves_saved);
    // Kept leaves from more rounds than one (2 048 leaves), so from several subgroups on any device.
    EXPECT_GT(most_kept, 2048u) << (instanced ? "instanced" : "pulled");
  }
}

// With MSAA the pyramid reads the resolved depth (sample 0): the hidden tree is found too.
TEST_F(OcclusionTest, MultisampledDepthFeedsThePyramid) {
  const TreeModel& m = broadleaf_with_hull();
  Scene s = make_scene({dense(m), m}, row_and_hidden_tree());
  Renderer r(ctx_, s, 120, 90, 4);
  ASSERT_GT(r.samples(), 1u);
  FrameSettings occl;
  occl.occlusion = true;
  for (int f = 0; f < 5; ++f) r.render(s.desc.camera, nullptr, occl);
  std::vector<gpu::InstanceState> st = r.instance_states();
  EXPECT_LE(st.back().occlusion, 0.15f);
  for (uint32_t i = 0; i < 3; ++i) EXPECT_GE(st[i].occlusion, 0.85f) << "front-row tree " << i;  // a dense crown hides its own far-side samples
}


// Leaves by vertex pulling (leaf_pulled.vert, the default) and as instances of their card
// (leaf.vert): the same frame, pixel for pixel, with occlusion (tail lists) and the sun's
// shadows (the shadow pass's leaf draws), and the same counts.
TEST_F(OcclusionTest, PulledAndInstancedLeavesDrawTheSameFrame) {
  Scene s = hidden_pruning_scene(broadleaf_with_hull());
  FrameImage images[2], masks[2];
  FrameStats stats[2];
  for (int instanced = 0; instanced < 2; ++instanced) {
    Renderer r(ctx_, s, 160, 120, 1);
    FrameSettings settings;
    settings.occlusion = true;
    settings.shadows = true;
    settings.prune_mode = PruneMode::cook;
    settings.instanced_leaves = instanced != 0;
    for (int f = 0; f < 4; ++f) r.render(s.desc.camera, nullptr, settings);
    stats[instanced] = r.render(s.desc.camera, &images[instanced], settings);
    FrameSettings mask = settings;
    mask.mask = true;
    r.render(s.desc.camera, &masks[instanced], mask);
  }
  EXPECT_GT(stats[0].leaves_saved, 0u) << "the tail lists are exercised";
  EXPECT_GT(stats[0].shadow_leaves[2] + stats[0].shadow_leaves[1] + stats[0].shadow_leaves[0], 0u);
  EXPECT_EQ(stats[0].leaves_drawn, stats[1].leaves_drawn);
  EXPECT_EQ(stats[0].leaves_saved, stats[1].leaves_saved);
  ASSERT_EQ(images[0].rgba.size(), images[1].rgba.size());
  // Both forms compute a leaf's corners by the same sums (leaf_body.glsl, leaf_card.geom), but
  // lavapipe's geometry-shader path may place a vertex a rounding step apart, which decides a
  // depth tie between two crossing cards here and there (1 pixel of this frame): allow 1 pixel
  // in 2 000. A wrong leaf, corner or transform in either form changes hundreds.
  const size_t pixels = images[0].rgba.size() / 4, allowed = pixels / 2000;
  EXPECT_LE(differing_pixels(images[0], images[1]), allowed) << "shaded frames differ";
  EXPECT_LE(differing_pixels(masks[0], masks[1]), allowed) << "coverage differs";
}
