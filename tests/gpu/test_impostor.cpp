// Impostors on lavapipe with the validation layer (engine/tools/bake/impostor_bake.h,
// engine/render/impostor_pass.h): the bake measures a good impostor, the cull pass switches to
// it only where PR says it is at least as good as the mesh, and impostors cast shadows.
#include <gtest/gtest.h>

#include <cstdio>

#include "engine/render/renderer.h"
#include "engine/tools/bake/tree_bake.h"
#include "engine/tools/report/popping.h"
#include "tests/gpu/gpu_scenes.h"
#include "tests/gpu/validated_gpu_test.h"

using namespace forest;
using namespace forest::test;

namespace {

class ImpostorTest : public ValidatedGpuTest {};

// Broadleaf baked on two views with tables from 128 px down to 4 px, impostor included.
const TreeModel& baked(vk::Context& ctx) {
  static TreeModel model;
  if (model.leaves.empty()) {
    model = broadleaf();
    TreeBakeSettings bake;
    bake.views = 2;
    bake.resolution = 128;
    bake_tree_model(ctx, model, bake);
  }
  return model;
}

// A grove of 30 trees on flat ground, pruned over 150 m.
Scene grove(const TreeModel& m) {
  SceneDesc desc = flat_ground(192, 128, 800.0f);
  desc.prune_distance = 150.0f;
  desc.placement.count = 30;
  desc.placement.seed = 5;
  desc.placement.min_spacing = 5.0f;
  desc.placement.radius = 30.0f;
  return scene_of(std::move(desc), {m});
}

CameraDesc looking_at_grove(float distance) {
  CameraDesc c;
  c.position = {0.0f, 6.0f, -distance};
  c.target = {0.0f, 4.0f, 0.0f};
  c.fov_deg = 40.0f;
  c.far = 5000.0f;
  return c;
}

// Where the popping path starts: far enough that most of the grove draws impostors; it ends
// 60 m nearer.
constexpr float kSwitchFrom = 95.0f;

uint64_t dark_pixels(const FrameImage& img) {
  uint64_t n = 0;
  for (size_t i = 0; i < img.rgba.size(); i += 4) n += img.rgba[i] < 128;
  return n;
}

}  // namespace

// Q of the impostor against full detail, pooled over the bake's views, at every table size:
// ≥ 0.75 (lavapipe: 0.80–0.88 from 128 to 8 px). A mirrored or turned view, or one sampled
// from the wrong cell, draws another silhouette: Q ≈ 0.4–0.6.
TEST_F(ImpostorTest, BakedImpostorMatchesTheMeshAtEverySize) {
  const TreeModel& m = baked(ctx_);
  ASSERT_TRUE(m.impostor.present());
  ASSERT_EQ(m.impostor.q.size(), size_t(PR_SIZES));
  for (uint32_t b = 0; b < PR_SIZES; ++b) {
    std::printf("impostor Q at %g px: %.3f\n", double(pr_size(m.bake.pr_tables->size0, b)), double(m.impostor.q[b]));
    if (pr_size(m.bake.pr_tables->size0, b) >= 8.0f) EXPECT_GE(m.impostor.q[b], 0.75f) << "size " << b;
  }
  std::printf("coverage cutoff %.2f\n", double(m.impostor.cutoff));
}

// The switch follows PR: most near trees keep their mesh, far ones take the impostor, mode full
// (Q = 1 everywhere) never does, and a far frame with impostors keeps Q within the equal-
// quality tolerance of the same frame without them. (The grove's far half, 10–20 px across
// from 40 m in this small frame, may switch: with leaves alpha-tested per sample in the
// impostor's 4x MSAA bake its Q rose by 0.03–0.06, and 9 of 34 trees there switched; that
// frame's Q is printed, not asserted: 0.9590 against 0.9612 without impostors on lavapipe.)
TEST_F(ImpostorTest, SwitchedWhereTheImpostorIsAsGoodAsTheMesh) {
  Scene scene = grove(baked(ctx_));
  Renderer r(ctx_, scene, 192, 128, 1);
  FrameSettings opt;
  opt.prune_mode = PruneMode::opt;
  opt.impostors = ImpostorMode::switched;
  FrameStats near = r.render(looking_at_grove(40.0f), nullptr, opt);
  FrameStats far = r.render(looking_at_grove(600.0f), nullptr, opt);
  FrameSettings full = opt;
  full.prune_mode = PruneMode::full;
  FrameStats far_full = r.render(looking_at_grove(600.0f), nullptr, full);
  std::printf("impostors near %u of %u, far %u of %u, full %u\n", near.impostors, near.branch_draws + near.impostors,
              far.impostors, far.branch_draws + far.impostors, far_full.impostors);
  EXPECT_LT(near.impostors, (near.branch_draws + near.impostors) / 2);
  EXPECT_GT(far.impostors, (far.branch_draws + far.impostors) / 2);
  EXPECT_EQ(far_full.impostors, 0u);

  FrameSettings mesh = opt;
  mesh.impostors = ImpostorMode::off;
  for (float distance : {40.0f, 600.0f}) {
    r.render_reference(looking_at_grove(distance), FrameSettings{});
    double q_mesh = r.compare_with_reference(looking_at_grove(distance), mesh).quality();
    double q_imp = r.compare_with_reference(looking_at_grove(distance), opt).quality();
    std::printf("frame at %g m, Q: opt %.4f, opt with impostors %.4f\n", double(distance), q_mesh, q_imp);
    if (distance > 100.0f) EXPECT_GE(q_imp, q_mesh - kEqualQualityTolerance);
  }
}

// An impostor casts its crown's shadow: seen from above with the sun's visibility shown, the
// ground under one tree drawn as its impostor is about as dark as under its mesh, and the
// cascades list it as an impostor caster.
TEST_F(ImpostorTest, ImpostorsCastShadows) {
  SceneDesc desc = flat_ground(160, 160, 200.0f);
  desc.trees.push_back(TreeDesc{});
  desc.sky.sun_direction = glm::normalize(glm::vec3(0.5f, 0.8f, 0.3f));
  Scene scene = scene_of(std::move(desc), {baked(ctx_)});
  Renderer r(ctx_, scene, 160, 160, 1);
  CameraDesc above;
  above.position = {0.5f, 45.0f, -12.0f};
  above.target = {-3.0f, 0.0f, -2.0f};
  above.fov_deg = 50.0f;
  FrameSettings s;
  s.shadows = true;
  s.shadow_view = true;
  FrameImage mesh, impostor, none;
  r.render(above, &mesh, s);
  s.impostors = ImpostorMode::always;
  FrameStats st = r.render(above, &impostor, s);
  s.shadows = false;
  r.render(above, &none, s);
  std::printf("dark pixels: mesh %llu, impostor %llu, no shadows %llu; impostor casters %u %u %u\n",
              (unsigned long long)dark_pixels(mesh), (unsigned long long)dark_pixels(impostor),
              (unsigned long long)dark_pixels(none), st.shadow_impostors[0], st.shadow_impostors[1],
              st.shadow_impostors[2]);
  EXPECT_EQ(st.shadow_casters[0] + st.shadow_casters[1] + st.shadow_casters[2], 0u);
  EXPECT_GT(st.shadow_impostors[0] + st.shadow_impostors[1] + st.shadow_impostors[2], 0u);
  EXPECT_GT(dark_pixels(mesh), 200u);
  EXPECT_GT(double(dark_pixels(impostor)), 0.6 * double(dark_pixels(mesh)));
  // The impostor's shadow is fuller than the mesh's: 1.53x with its views drawn at full
  // detail, 1.64x pruned to Q 0.98 by phase-averaged tables (stop 33). It was 1.10x only while
  // one-phase tables pruned those views further than Q 0.98.
  EXPECT_LT(double(dark_pixels(impostor)), 1.8 * double(dark_pixels(mesh)));
}

// The mesh-to-impostor switch, measured like branch LOD popping (engine/tools/report/popping.h,
// test_popping.cpp: the LOD viewpoint one frame ahead, coverage compared): flying at 9 m/s and
// 30 fps from 95 m to 35 m, where the grove's trees trade impostors for meshes (about 20 px
// across there), the dithered cross-fade flips no solid group of pixels larger than the bound
// branch LODs keep (0.08 % of the frame) and on average <= 2 % of the tree pixels a frame
// (lavapipe: mean 0.2 %, worst step 0.7 %, no solid group). The control: every tree switched at
// once, without a band (the meshes of one frame against the impostors of the same frame),
// flips several times the worst step's share.
TEST_F(ImpostorTest, TheSwitchPopsNoMoreThanBranchLods) {
  Scene scene = grove(baked(ctx_));
  Renderer r(ctx_, scene, 192, 128, 1);
  FrameSettings opt;
  opt.prune_mode = PruneMode::opt;
  opt.impostors = ImpostorMode::switched;
  std::vector<CameraDesc> path;
  for (int f = 0; f <= 200; ++f) path.push_back(looking_at_grove(kSwitchFrom - 0.3f * float(f)));
  const FrameStats first = r.render(path.front(), nullptr, opt), last = r.render(path.back(), nullptr, opt);
  std::printf("impostors at %.0f m: %u of %u, at %.0f m: %u of %u\n", double(kSwitchFrom), first.impostors,
              first.impostors + first.branch_draws, double(kSwitchFrom - 60.0f), last.impostors,
              last.impostors + last.branch_draws);
  ASSERT_GE(first.impostors, last.impostors + 5) << "the path must cross the switch of several trees";
  PopWalk w = measure_popping(r, path, opt);
  const uint64_t max_blob = 192u * 128u * 8u / 10000u;
  PopStep s = w.worst_share();
  std::printf("impostor switch: mean %.4f, worst %.4f, largest solid blob %llu px (bound %llu)\n", w.mean_share(),
              s.share(), (unsigned long long)w.worst_solid_blob().largest_solid_blob, (unsigned long long)max_blob);
  EXPECT_LE(w.worst_solid_blob().largest_solid_blob, max_blob);
  EXPECT_LE(w.mean_share(), 0.02);
  EXPECT_GT(w.mean_share(), 0.0);
  // What the band itself does: the switch of trees this small stays within the branch bound
  // even without it (lavapipe, band 0.0001: worst step 2.0 %, a 14 px solid group); with it
  // every step stays scattered, within a quarter of that bound.
  EXPECT_LE(w.worst_solid_blob().largest_solid_blob, max_blob / 4);
  EXPECT_LE(s.share(), 0.01);

  FrameSettings mask = opt;
  mask.mask = true;
  FrameImage meshes, impostors;
  mask.impostors = ImpostorMode::off;
  r.render(path[100], &meshes, mask);
  mask.impostors = ImpostorMode::always;
  r.render(path[100], &impostors, mask);
  PopStep instant = measure_pop(meshes, impostors);
  std::printf("instant switch of every tree: %llu of %llu px (%.4f), largest solid blob %llu px\n",
              (unsigned long long)instant.changed, (unsigned long long)instant.covered, instant.share(),
              (unsigned long long)instant.largest_solid_blob);
  EXPECT_GT(instant.share(), 4.0 * s.share()) << "the measure does not see an unfaded switch";
}
