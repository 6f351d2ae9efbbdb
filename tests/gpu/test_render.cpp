// Renders tiny scenes on the Vulkan device (lavapipe in CI) with the validation layer on,
// and checks pixel properties: sky above, terrain below, trees exactly where they project.
#include <gtest/gtest.h>

#include <cmath>

#include <cstring>

#include "engine/tools/gallery/contact_sheet.h"
#include "engine/render/renderer.h"
#include "generators/asset/pr_tables.h"
#include "prune_math.h"
#include "engine/scene/scene.h"
#include "tests/gpu/gpu_scenes.h"
#include "tests/gpu/validated_gpu_test.h"

using namespace forest;
using namespace forest::test;

namespace {

// Single-sampled unless asked: lavapipe's cost grows with the sample count.
std::string tiny_scene(const std::string& extra, uint32_t samples = 1) {
  return SceneText{.samples = samples, .extra = extra}.str();
}

struct Rendered {
  FrameImage image;
  FrameStats stats;
  Scene scene;
};

class GpuTest : public ValidatedGpuTest {
 protected:
  Rendered render(const std::string& text) {
    Rendered r;
    SceneDesc desc = parse_scene(text);
    r.scene = build_scene(desc);
    Renderer renderer(ctx_, r.scene, desc.width, desc.height, desc.samples);
    r.stats = renderer.render(desc.camera, &r.image);
    return r;
  }
};

bool is_sky(const uint8_t* p) { return p[2] > p[0] && p[2] >= p[1] && p[2] > 120; }

// Terrain and trees are green/brown: blue is the weakest channel.
bool is_vegetation_or_ground(const uint8_t* p) { return p[2] < p[1] && p[2] <= p[0] + 8; }

size_t count_differences(const FrameImage& a, const FrameImage& b, int x0, int y0, int x1, int y1, bool inside) {
  size_t n = 0;
  for (int y = 0; y < int(a.height); ++y)
    for (int x = 0; x < int(a.width); ++x) {
      bool in = x >= x0 && x <= x1 && y >= y0 && y <= y1;
      if (in != inside) continue;
      const uint8_t *p = a.pixel(uint32_t(x), uint32_t(y)), *q = b.pixel(uint32_t(x), uint32_t(y));
      if (p[0] != q[0] || p[1] != q[1] || p[2] != q[2]) ++n;
    }
  return n;
}

}  // namespace

TEST_F(GpuTest, SkyAboveTerrainBelow) {
  Rendered r = render(tiny_scene(""));
  const FrameImage& img = r.image;
  ASSERT_EQ(img.width, 160u);
  ASSERT_EQ(img.height, 120u);
  for (uint32_t x = 0; x < img.width; x += 8) {
    EXPECT_TRUE(is_sky(img.pixel(x, 2))) << "top row pixel " << x << " is not sky";
    EXPECT_TRUE(is_vegetation_or_ground(img.pixel(x, img.height - 3))) << "bottom row pixel " << x << " is not terrain";
  }
  // The horizon: sky meets terrain roughly where the camera's horizontal plane projects.
  CameraMatrices cm = camera_matrices(r.scene.desc.camera, 160.0f / 120.0f);
  glm::vec3 far_ground = project_to_pixel(cm, glm::vec3(0.0f, 0.0f, 95.0f), 160.0f, 120.0f);
  int y_sky = int(far_ground.y) - 6, y_ground = int(far_ground.y) + 6;
  ASSERT_GT(y_sky, 0);
  ASSERT_LT(y_ground, 120);
  EXPECT_TRUE(is_sky(img.pixel(80, uint32_t(y_sky))));
  EXPECT_FALSE(is_sky(img.pixel(80, uint32_t(y_ground))));
  EXPECT_EQ(r.stats.instances, 0u);
  EXPECT_EQ(r.stats.branch_draws, 0u);
}

TEST_F(GpuTest, TreeDrawnExactlyWhereItProjects) {
  // Without the sun's shadows: the tree's shadow on the ground falls outside its sphere.
  auto scene = [](const std::string& extra) {
    return SceneText{.samples = 1, .render = "shadows = false\n", .extra = extra}.str();
  };
  Rendered bare = render(scene(""));
  Rendered tree = render(scene("[[tree]]\nspecies = 0\nx = 0\nz = 0\n"));
  ASSERT_EQ(tree.stats.instances, 1u);
  EXPECT_EQ(tree.stats.branch_draws, 1u);
  EXPECT_EQ(tree.stats.leaf_draws, 1u);
  EXPECT_EQ(tree.stats.leaves_drawn, tree.scene.models[0].leaves.size());

  // Screen rectangle of the instance's bounding sphere.
  const gpu::Instance& inst = tree.scene.instances[0];
  glm::vec4 s = tree.scene.models[0].bounding_sphere;
  glm::vec3 c = glm::vec3(inst.position_scale) + glm::vec3(s) * inst.position_scale.w;  // yaw 0
  float r = s.w * inst.position_scale.w;
  CameraMatrices cm = camera_matrices(tree.scene.desc.camera, 160.0f / 120.0f);
  float x0 = 1e9f, y0 = 1e9f, x1 = -1e9f, y1 = -1e9f;
  for (int i = 0; i < 8; ++i) {
    glm::vec3 corner = c + r * glm::vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
    glm::vec3 p = project_to_pixel(cm, corner, 160.0f, 120.0f);
    x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
  }
  size_t inside = count_differences(bare.image, tree.image, int(x0) - 1, int(y0) - 1, int(x1) + 1, int(y1) + 1, true);
  size_t outside = count_differences(bare.image, tree.image, int(x0) - 1, int(y0) - 1, int(x1) + 1, int(y1) + 1, false);
  EXPECT_EQ(outside, 0u) << "tree pixels outside its projected bounding sphere";
  EXPECT_GT(inside, 150u) << "the tree covers too few pixels";

  // The trunk, a third of the way up, is tree-colored (not sky) on the tree's axis.
  glm::vec3 trunk = project_to_pixel(cm, glm::vec3(inst.position_scale) + glm::vec3(0, 0.5f, 0), 160.0f, 120.0f);
  const uint8_t* p = tree.image.pixel(uint32_t(trunk.x), uint32_t(trunk.y));
  const uint8_t* q = bare.image.pixel(uint32_t(trunk.x), uint32_t(trunk.y));
  EXPECT_TRUE(p[0] != q[0] || p[1] != q[1] || p[2] != q[2]) << "no tree at the trunk's pixel";
  EXPECT_FALSE(is_sky(p));
  // The crown (above the trunk) replaces sky by vegetation.
  glm::vec3 crown = project_to_pixel(cm, glm::vec3(c), 160.0f, 120.0f);
  size_t green = 0;
  for (int dy = -3; dy <= 3; ++dy)
    for (int dx = -3; dx <= 3; ++dx) {
      const uint8_t* g = tree.image.pixel(uint32_t(crown.x + dx), uint32_t(crown.y + dy));
      green += g[1] > g[2] && g[1] >= g[0];
    }
  EXPECT_GT(green, 20u) << "the crown around the bounding-sphere center is not leaf-colored";
}

TEST_F(GpuTest, TreeBehindCameraIsCulledOnTheGpu) {
  Rendered bare = render(tiny_scene(""));
  Rendered behind = render(tiny_scene("[[tree]]\nspecies = 0\nx = 0\nz = -60\n"));
  EXPECT_EQ(behind.stats.instances, 1u);
  EXPECT_EQ(behind.stats.branch_draws, 0u);
  EXPECT_EQ(behind.stats.leaves_drawn, 0u);
  EXPECT_EQ(count_differences(bare.image, behind.image, 0, 0, -1, -1, false), 0u);
}

TEST_F(GpuTest, ThousandInstancesAllVisibleFromAbove) {
  // Camera high above, looking down: every tree is in the frustum, so the GPU must emit one
  // branch and one leaf draw per instance and draw every leaf of every tree.
  Rendered r = render(SceneText{.position = {0.0f, 400.0f, -1.0f},
                                 .target = {0.0f, 0.0f, 0.0f},
                                 .extra = "[placement]\ncount = 1000\nseed = 5\nmin_spacing = 2.0\nradius = 60\n"}
                          .str());
  ASSERT_EQ(r.stats.instances, 1000u);
  EXPECT_EQ(r.stats.branch_draws, 1000u);
  EXPECT_EQ(r.stats.leaf_draws, 1000u);
  EXPECT_EQ(uint64_t(r.stats.leaves_drawn), uint64_t(1000) * r.scene.models[0].leaves.size());
  // Seen from above, the forest floor is mostly covered by crowns: lots of leaf green
  // in the centre of the image.
  size_t green = 0, total = 0;
  for (uint32_t y = 40; y < 80; ++y)
    for (uint32_t x = 60; x < 100; ++x, ++total) {
      const uint8_t* p = r.image.pixel(x, y);
      green += p[1] > p[0] && p[1] > p[2];
    }
  EXPECT_GT(green, total / 4);
}

TEST_F(GpuTest, SameSceneRendersIdentically) {
  Rendered a = render(tiny_scene("[[tree]]\nspecies = 0\nx = 1\nz = 2\nyaw = 40\n"));
  Rendered b = render(tiny_scene("[[tree]]\nspecies = 0\nx = 1\nz = 2\nyaw = 40\n"));
  EXPECT_EQ(a.image.rgba, b.image.rgba);
}

TEST_F(GpuTest, MultisamplingResolvesEdgesOnly) {
  const std::string tree = "[[tree]]\nspecies = 0\nx = 0\nz = 0\n";
  Rendered a = render(tiny_scene(tree, 1)), b = render(tiny_scene(tree, 4));
  size_t differ = count_differences(a.image, b.image, 0, 0, -1, -1, false);
  EXPECT_GT(differ, 30u) << "4x MSAA changed no edge pixel";
  EXPECT_LT(differ, size_t(160 * 120) / 4) << "MSAA changed far more than edges";
  // Interior sky is the same with and without multisampling.
  for (uint32_t x = 0; x < 160; x += 4)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(a.image.pixel(x, 3)[c], b.image.pixel(x, 3)[c], 1);
}

namespace {
// A scene holding one model, built directly (no species file): for engine-only properties.
Scene single_model_scene(TreeModel model, std::vector<TreeDesc> trees, float lod_error_pixels = 1.0f) {
  SceneDesc desc = parse_scene(tiny_scene(""));
  desc.species.clear();
  desc.trees = std::move(trees);
  desc.lod_error_pixels = lod_error_pixels;
  return scene_of(std::move(desc), {std::move(model)});
}
}  // namespace

TEST_F(GpuTest, BranchLodChosenByProjectedError) {
  TreeModel m = broadleaf();
  m.branch_lods.clear();
  // Three fake coarser levels (copies) with growing errors: the choice depends only on them.
  for (float e : {0.2f, 0.5f, 2.0f}) m.branch_lods.push_back({m.branches, e});
  std::vector<TreeDesc> trees = {{0, 0.0f, 0.0f, 1.0f, 0.0f}, {0, 0.0f, 60.0f, 1.0f, 0.0f}, {0, 0.0f, 95.0f, 1.0f, 0.0f}};
  Scene s = single_model_scene(m, trees);
  s.desc.terrain.size = 400;
  s.terrain = make_terrain(s.desc.terrain);
  Renderer r(ctx_, s, 160, 120, 1);
  FrameStats stats = r.render(s.desc.camera, nullptr);
  ASSERT_EQ(stats.branch_draws, 3u);
  // Expected level per tree from the same rule on the CPU.
  float ppm = focal_pixels(120.0f, s.desc.camera.fov_deg);
  uint32_t expected[MAX_BRANCH_LODS] = {};
  for (const gpu::Instance& inst : s.instances) {
    glm::vec3 c = glm::vec3(inst.position_scale) + glm::vec3(m.bounding_sphere);
    float dist = std::max(glm::distance(c, s.desc.camera.position) - m.bounding_sphere.w, 1e-3f);
    uint32_t lod = 0;
    for (uint32_t k = 1; k < 4; ++k)
      if (m.branch_lods[k - 1].error * ppm / dist <= 1.0f) lod = k;
    expected[lod]++;
  }
  for (int k = 0; k < MAX_BRANCH_LODS; ++k) EXPECT_EQ(stats.lod_draws[k], expected[k]) << "LOD " << k;
  EXPECT_GT(stats.lod_draws[0], 0u);
  EXPECT_LT(stats.lod_draws[0], 3u) << "far trees should use coarser levels";

  Scene full = single_model_scene(m, trees, 0.0f);  // 0 px allowed: always LOD0
  Renderer r0(ctx_, full, 160, 120, 1);
  EXPECT_EQ(r0.render(full.desc.camera, nullptr).lod_draws[0], 3u);
}

TEST_F(GpuTest, TransparentLeafTextureHidesLeaves) {
  TreeModel textured = broadleaf(), leafless = broadleaf();
  textured.leaf_texture.width = textured.leaf_texture.height = 8;
  textured.leaf_texture.rgba.assign(8 * 8 * 4, 0);  // alpha 0 everywhere
  leafless.leaves.clear();
  std::vector<TreeDesc> tree = {{0, 0.0f, 0.0f, 1.0f, 0.0f}};
  for (uint32_t samples : {1u, 4u}) {
    Scene a = single_model_scene(textured, tree), b = single_model_scene(leafless, tree);
    Renderer ra(ctx_, a, 160, 120, samples), rb(ctx_, b, 160, 120, samples);
    FrameImage ia, ib;
    ra.render(a.desc.camera, &ia);
    rb.render(b.desc.camera, &ib);
    EXPECT_EQ(count_differences(ia, ib, 0, 0, -1, -1, false), 0u) << samples << " samples";
  }
  // And an opaque texture shows them.
  TreeModel opaque = broadleaf();
  opaque.leaf_texture.width = opaque.leaf_texture.height = 8;
  opaque.leaf_texture.rgba.assign(8 * 8 * 4, 255);
  Scene a = single_model_scene(opaque, tree), b = single_model_scene(leafless, tree);
  Renderer ra(ctx_, a, 160, 120, 1), rb(ctx_, b, 160, 120, 1);
  FrameImage ia, ib;
  ra.render(a.desc.camera, &ia);
  rb.render(b.desc.camera, &ib);
  EXPECT_GT(count_differences(ia, ib, 0, 0, -1, -1, false), 100u);
}

TEST_F(GpuTest, TurntableFramesTheModel) {
  TurntableOptions t;
  t.size = 96;
  t.views = 4;
  t.samples = 1;
  std::vector<FrameImage> views = render_turntable(ctx_, broadleaf(), t);
  ASSERT_EQ(views.size(), 4u);
  for (const FrameImage& v : views) {
    // The model fills the middle (a third of the central box is not sky), and the top row is
    // all sky: nothing is cut off at the top.
    size_t solid = 0;
    for (uint32_t y = 32; y < 64; ++y)
      for (uint32_t x = 32; x < 64; ++x) solid += !is_sky(v.pixel(x, y));
    EXPECT_GT(solid, 32u * 32u / 3u);
    size_t sky_top = 0;
    for (uint32_t x = 0; x < 96; ++x) sky_top += is_sky(v.pixel(x, 1));
    EXPECT_EQ(sky_top, 96u) << "the crown touches the top edge";
  }
  EXPECT_NE(views[0].rgba, views[1].rgba);  // different azimuths
  FrameImage sheet = compose_grid(views, 2, 4);
  EXPECT_EQ(sheet.width, 2u * 96u + 3u * 4u);
  EXPECT_EQ(sheet.height, 2u * 96u + 3u * 4u);
  EXPECT_EQ(0, std::memcmp(sheet.pixel(4, 4), views[0].pixel(0, 0), 4));
  EXPECT_EQ(0, std::memcmp(sheet.pixel(4 + 96 + 4, 4 + 96 + 4), views[3].pixel(0, 0), 4));
}

namespace {

// Cook's leaves for every tree of `scene` seen from `camera`, done on the CPU with the
// shaders' arithmetic (shaders/prune_math.h): per tree λ = (1 − d)², d = distance ÷
// `prune_distance`, and k = ⌈λN⌉ leaves; the sum of k, and the mean λ.
std::pair<uint64_t, double> cook_reference(const Scene& scene, glm::vec3 camera, float prune_distance) {
  const TreeModel& m = scene.models[0];
  uint64_t leaves = 0;
  double lambda_sum = 0;
  for (const gpu::Instance& inst : scene.instances) {
    glm::vec3 c = glm::vec3(inst.position_scale) +
                  glm::vec3(inst.yaw_cos_sin.x * m.bounding_sphere.x + inst.yaw_cos_sin.y * m.bounding_sphere.z,
                            m.bounding_sphere.y,
                            -inst.yaw_cos_sin.y * m.bounding_sphere.x + inst.yaw_cos_sin.x * m.bounding_sphere.z) *
                      inst.position_scale.w;
    float lambda = prune::lambda_cook(std::clamp(glm::distance(c, camera) / prune_distance, 0.0f, 1.0f));
    lambda_sum += lambda;
    leaves += prune::leaf_prefix(lambda, uint32_t(m.leaves.size()));
  }
  return {leaves, lambda_sum / double(scene.instances.size())};
}

const SceneText kCookStand{.render = "mode = \"cook\"\nprune_distance = 220\n",
                           .position = {0.0f, 150.0f, -1.0f},
                           .target = {0.0f, 0.0f, 0.0f},
                           .extra = "[placement]\ncount = 300\nseed = 9\nmin_spacing = 2.0\nradius = 60\n"};

}  // namespace

TEST_F(GpuTest, CookLeafCountsMatchCpuReference) {
  // Every tree visible from above; the GPU's per-tree λ = (1 − d)² and k = ⌈λN⌉ summed must
  // equal the same arithmetic done here.
  Rendered r = render(kCookStand.str());
  ASSERT_EQ(r.stats.branch_draws, 300u);
  auto [expected, mean_lambda] = cook_reference(r.scene, r.scene.desc.camera.position, 220.0f);
  // ±1 leaf per tree for float rounding differences between the GPU and the CPU.
  EXPECT_NEAR(double(r.stats.leaves_drawn), double(expected), 300.0);
  EXPECT_LT(r.stats.leaves_drawn, 300u * r.scene.models[0].leaves.size() / 2) << "Cook at d ~ 0.7 should drop most leaves";
  EXPECT_NEAR(r.stats.mean_lambda, mean_lambda, 1e-3);
}

TEST_F(GpuTest, PruneDistanceScalesWithTheFramesPixels) {
  // The scene states prune_distance for its own 120-pixel-high frame at fov 50°. Twice the
  // height shows every tree on more pixels, half of it or a wider fov on fewer: the distance
  // scales by the focal lengths' ratio, so a tree keeps the λ it has where it covers as many pixels.
  SceneDesc desc = parse_scene(kCookStand.str());
  Scene scene = build_scene(desc);
  const float focal = focal_pixels(120.0f, 50.0f);
  ASSERT_FLOAT_EQ(scene.desc.prune_focal_pixels, focal);
  struct Frame { uint32_t width, height; float fov; };
  for (Frame f : {Frame{320, 240, 50.0f}, Frame{80, 60, 50.0f}, Frame{160, 120, 70.0f}}) {
    SCOPED_TRACE(std::to_string(f.height) + " px high, fov " + std::to_string(f.fov));
    CameraDesc camera = desc.camera;
    camera.fov_deg = f.fov;
    Renderer renderer(ctx_, scene, f.width, f.height, 1);
    FrameStats st = renderer.render(camera, nullptr);
    const float distance = 220.0f * focal_pixels(float(f.height), f.fov) / focal;
    auto [expected, mean_lambda] = cook_reference(scene, camera.position, distance);
    const uint64_t unscaled = cook_reference(scene, camera.position, 220.0f).first;
    ASSERT_GT(std::abs(double(expected) - double(unscaled)), 3000.0);  // the frames differ enough to tell
    EXPECT_NEAR(double(st.leaves_drawn), double(expected), 300.0);
    EXPECT_NEAR(st.mean_lambda, mean_lambda, 1e-3);
  }
}

TEST_F(GpuTest, OptAtFullDetailEqualsFull) {
  // A model whose tables say λ = 1 and s = 1 everywhere must render exactly like `full`.
  TreeModel m = broadleaf();
  PrSizeTables t;
  t.s_opt.assign(S_SAMPLES, 1.0f);
  t.q_opt.assign(S_SAMPLES, 1.0f);
  t.q_inverse.assign(S_SAMPLES, 1.0f);
  t.lambda_opt.assign(D_SAMPLES, 1.0f);
  t.s_far.assign(F_SAMPLES, 1.0f);
  t.q_far.assign(F_SAMPLES, 1.0f);
  t.q_inverse_far.assign(F_SAMPLES, 1.0f);
  t.q_low.assign(S_SAMPLES, 1.0f);
  t.q_low_far.assign(F_SAMPLES, 1.0f);
  m.bake.pr_tables = pr_tables_at_every_size(t);
  std::vector<TreeDesc> trees = {{0, 0.0f, 0.0f, 1.0f, 0.0f}, {0, 5.0f, 20.0f, 1.0f, 30.0f}};
  Scene s = single_model_scene(m, trees);
  Renderer r(ctx_, s, 160, 120, 1);
  FrameSettings full, opt;
  opt.prune_mode = PruneMode::opt;
  FrameImage a, b;
  FrameStats sa = r.render(s.desc.camera, &a, full), sb = r.render(s.desc.camera, &b, opt);
  EXPECT_EQ(sa.leaves_drawn, sb.leaves_drawn);
  EXPECT_EQ(a.rgba, b.rgba);
  // And tables that halve λ draw half the leaves.
  t.lambda_opt.assign(D_SAMPLES, 0.5f);
  m.bake.pr_tables = pr_tables_at_every_size(t);
  Scene half = single_model_scene(m, trees);
  Renderer rh(ctx_, half, 160, 120, 1);
  EXPECT_EQ(rh.render(half.desc.camera, nullptr, opt).leaves_drawn, 2 * prune::leaf_prefix(0.5f, uint32_t(m.leaves.size())));
}

namespace {

// One far check of OptFarLeafAreaFollowsTheFarSamples: at u = log2(1/20 / λ), opt's render is
// the fixed render at (λ, the expected s) and differs from the fixed render at the s a wrong
// rule would give.
void check_far_scale(vk::Context& ctx, const TreeModel& m, float u) {
  SCOPED_TRACE("n = " + std::to_string(m.leaves.size()) + ", u = " + std::to_string(u));
  Scene s = single_model_scene(m, {{0, 0.0f, 0.0f, 1.0f, 0.0f}});
  ASSERT_EQ(s.instances.size(), 1u);
  const gpu::Instance& inst = s.instances[0];  // yaw 0, scale 1: the sphere shifted to the tree
  ASSERT_FLOAT_EQ(inst.yaw_cos_sin.x, 1.0f);
  const glm::vec3 centre = glm::vec3(inst.position_scale) + glm::vec3(m.bounding_sphere) * inst.position_scale.w;
  s.desc.camera.position = centre + glm::vec3(0.0f, 2.0f, -4.0f * m.bounding_sphere.w);
  s.desc.camera.target = centre;
  const float distance = glm::distance(s.desc.camera.position, centre);
  const float lambda = 1.0f / (20.0f * std::exp2(u));
  const float d = 1.0f - std::sqrt(lambda);
  s.desc.prune_distance = distance / d;
  Renderer r(ctx, s, 160, 120, 1);
  const uint32_t n = uint32_t(m.leaves.size());
  float expected = 0, straight = 0;
  const float last = prune::far_lambda(F_SAMPLES - 1);
  auto blend_at = [&](float l) { return (1.0f + (last * 80.0f - 1.0f) * l / last) / l; };
  if (u < 2.0f) {
    expected = std::exp2(0.5f * (std::log2(10.0f) + std::log2(40.0f)));  // 20
    straight = 25.0f;
  } else if (u < 4.0f) {
    expected = blend_at(lambda);
    straight = 1.0f / lambda;  // Cook's s, a straight line to λ = 0 of the area fraction
  } else {
    // One leaf: Cook's clamp λ ≥ 10⁻³ and the crown's n / max(λn, 1) = n, whichever is
    // smaller; the wrong rule drops the one that binds.
    ASSERT_EQ(prune::leaf_prefix(prune::lambda_cook(d), n), 1u);
    const float clamped = blend_at(std::max(lambda, 1e-3f));
    expected = std::min(clamped, float(n));
    straight = clamped > float(n) ? clamped : std::min(blend_at(lambda), float(n));
    ASSERT_GT(straight, 1.5f * expected);
  }
  FrameSettings opt, fixed, wrong;
  opt.prune_mode = PruneMode::opt;
  fixed.prune_mode = wrong.prune_mode = PruneMode::fixed;
  fixed.fixed_lambda = wrong.fixed_lambda = prune::lambda_cook(d);
  fixed.fixed_scale = expected;
  wrong.fixed_scale = straight;
  opt.mask = fixed.mask = wrong.mask = true;
  FrameImage a, b, c;
  FrameStats so = r.render(s.desc.camera, &a, opt);
  r.render(s.desc.camera, &b, fixed);
  r.render(s.desc.camera, &c, wrong);
  EXPECT_EQ(so.leaves_drawn, prune::leaf_prefix(fixed.fixed_lambda, n));
  EXPECT_GT(so.leaves_drawn, u < 4.0f ? 3u : 0u);
  auto differing = [](const FrameImage& x, const FrameImage& y) {
    size_t count = 0;
    for (size_t i = 0; i < x.rgba.size(); i += 4) count += (x.rgba[i] > 127) != (y.rgba[i] > 127);
    return count;
  };
  EXPECT_LE(differing(a, b), 4u);
  EXPECT_GT(differing(a, c), 40u);
}

}  // namespace

TEST_F(GpuTest, OptFarLeafAreaFollowsTheFarSamples) {
  // Below λ = 1/20 opt draws Cook's λ with the tables' far s (tree_detail.glsl opt_area_scale):
  // log s interpolated in log λ between the far samples, past the last one a blend toward
  // Cook's 1/λ (λ clamped at 10⁻³), and never more area than the crown's n leaves.
  PrSizeTables t;
  t.s_opt.assign(S_SAMPLES, 5.0f);
  t.q_opt.assign(S_SAMPLES, 0.5f);
  t.q_inverse.assign(S_SAMPLES, 0.4f);
  t.lambda_opt.assign(D_SAMPLES, 0.5f);
  t.s_far = {10.0f, 40.0f, 80.0f};
  t.q_far.assign(F_SAMPLES, 0.3f);
  t.q_inverse_far.assign(F_SAMPLES, 0.2f);
  t.q_low.assign(S_SAMPLES, 0.3f);
  t.q_low_far.assign(F_SAMPLES, 0.1f);
  TreeModel m = broadleaf();
  m.bake.pr_tables = pr_tables_at_every_size(t);
  const float n = float(m.leaves.size());
  ASSERT_GT(n, 2000.0f);  // past the last sample, one leaf: the clamp binds before n does
  // u = log2(1/20 / λ): 1.5 lies between far samples 0 and 1, 3.5 past the last, and λ = 1/(2n)
  // draws one leaf.
  for (float u : {1.5f, 3.5f, std::log2(2.0f * n / 20.0f)}) check_far_scale(ctx_, m, u);
  // Its first 300 leaves, 4× as large (visible at one leaf): there n binds before the clamp.
  m.leaves.resize(300);
  for (LeafPlacement& leaf : m.leaves) leaf.scale *= 4.0f;
  check_far_scale(ctx_, m, std::log2(2.0f * 300.0f / 20.0f));
}
