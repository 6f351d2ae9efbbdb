// Light in the forest ([3/6]): the sun's cascaded shadow maps (stable under a moving camera,
// cast by trees outside the view, pruned with the trees), leaves that scatter the light
// through them toward a viewer who looks at the sun, and coverage that never depends on light.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/render/renderer.h"
#include "engine/scene/camera.h"
#include "engine/scene/scene.h"
#include "generators/mesh/leaf_texture.h"
#include "generators/mesh/mesher.h"
#include "tests/gpu/gpu_scenes.h"
#include "tests/gpu/validated_gpu_test.h"

using namespace forest;
using namespace forest::test;

namespace {

float linear(uint8_t v) {
  float c = float(v) / 255.0f;
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// Broadleaf trees on flat ground in a grid, sun from the south-west at 40°.
Scene grove(uint32_t size, glm::vec3 sun = glm::normalize(glm::vec3(-0.5f, 0.85f, -0.4f))) {
  SceneDesc d = flat_ground(size, size, 200.0f);
  d.sky.sun_direction = sun;
  for (int i = 0; i < 9; ++i) d.trees.push_back(TreeDesc{0, float(i % 3) * 9.0f - 9.0f, float(i / 3) * 9.0f - 9.0f, 1.0f,
                                                          float(i) * 40.0f});
  return scene_of(std::move(d), {broadleaf()});
}

// Looking straight down from `height` over (x, z) with a 60° field of view.
CameraDesc top_down(float x, float z, float height) {
  CameraDesc c;
  c.position = {x, height, z};
  c.target = {x, 0.0f, z};
  c.fov_deg = 60.0f;
  c.near = 0.5f;
  return c;
}

}  // namespace

class Light : public ValidatedGpuTest {};

// Slides the camera 0.1 m per frame over ground that one pixel spans 0.1 m of, so a fixed
// ground point lands on the same spot of a pixel one pixel over: any change in its shadow
// state comes from the shadow map moving under it. Stabilized cascades (whole-texel snapping)
// keep <= 0.5 % of the points visible in both frames in the same state.
TEST_F(Light, ShadowsStayPutUnderASlidingCamera) {
  const uint32_t size = 256;
  Scene s = grove(size);
  // Pixel footprint on the ground: 2 h tan(30°) / size = 0.1 m.
  const float height = 0.1f * float(size) / (2.0f * std::tan(glm::radians(30.0f)));
  Renderer renderer(ctx_, s, size, size, 1);
  FrameSettings shadow;
  shadow.shadows = true;
  shadow.shadow_view = true;
  FrameSettings mask;
  mask.mask = true;
  // Where a fixed ground point moves on the screen from one frame to the next (one pixel).
  const CameraMatrices m0 = camera_matrices(top_down(0.05f, 0.05f, height), 1.0f),
                       m1 = camera_matrices(top_down(0.15f, 0.05f, height), 1.0f);
  const glm::vec3 shift = project_to_pixel(m1, {3.0f, 0.0f, 2.0f}, float(size), float(size)) -
                          project_to_pixel(m0, {3.0f, 0.0f, 2.0f}, float(size), float(size));
  ASSERT_NEAR(std::abs(shift.x), 1.0f, 1e-3f);
  ASSERT_NEAR(shift.y, 0.0f, 1e-3f);
  const int dx = shift.x > 0.0f ? 1 : -1;
  size_t both = 0, changed = 0, shadowed = 0;
  FrameImage prev_shadow, prev_mask;
  for (int frame = 0; frame < 6; ++frame) {
    CameraDesc cam = top_down(0.1f * float(frame) + 0.05f, 0.05f, height);
    FrameImage sh, mk;
    renderer.render(cam, &sh, shadow);
    renderer.render(cam, &mk, mask);
    if (frame > 0)
      // The ground point under pixel (x, y) of the previous frame is under (x + dx, y) now.
      for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 1; x + 1 < size; ++x) {
          const uint32_t nx = uint32_t(int(x) + dx);
          if (prev_mask.pixel(x, y)[0] > 0 || mk.pixel(nx, y)[0] > 0) continue;  // a tree in front
          bool a = prev_shadow.pixel(x, y)[0] < 128, b = sh.pixel(nx, y)[0] < 128;
          ++both;
          shadowed += a;
          changed += a != b;
        }
    prev_shadow = std::move(sh);
    prev_mask = std::move(mk);
  }
  ASSERT_GT(both, 100000u);
  EXPECT_GT(double(shadowed) / double(both), 0.05) << "the trees should shade part of the ground";
  EXPECT_LE(double(changed) / double(both), 0.005) << changed << " of " << both << " ground points changed shadow state";
}

// A tree behind the camera still shades the ground the camera sees, and the shadow is that of
// the pruned tree: fewer leaves cast less shadow.
TEST_F(Light, TreesOutsideTheViewCastTheirPrunedShadow) {
  const uint32_t size = 160;
  SceneDesc d = flat_ground(size, size, 200.0f);
  d.sky.sun_direction = glm::normalize(glm::vec3(0.0f, 0.6f, -1.0f));  // low, from -z: shadows fall toward +z
  d.trees = {TreeDesc{0, 0.0f, 0.0f, 1.0f, 0.0f}};
  Scene s = scene_of(std::move(d), {broadleaf()});
  Renderer renderer(ctx_, s, size, size, 1);
  // The camera stands over the shadow, beyond the tree, looking away from it along +z.
  CameraDesc cam;
  cam.position = {0.0f, 6.0f, 6.0f};
  cam.target = {0.0f, 0.0f, 16.0f};
  cam.fov_deg = 70.0f;
  CameraMatrices cm = camera_matrices(cam, 1.0f);
  glm::vec4 base = cm.view_proj * glm::vec4(0.0f, 0.5f, 0.0f, 1.0f);
  ASSERT_LT(base.w, 0.0f) << "the tree must be behind the camera";
  FrameSettings off;
  off.shadow_view = true;
  FrameImage lit;
  renderer.render(cam, &lit, off);
  // Darkness the shadows add: per pixel, the visibility lost against the frame without them.
  auto shadowed = [&](float lambda) {
    FrameSettings f;
    f.shadows = true;
    f.shadow_view = true;
    f.prune_mode = PruneMode::fixed;
    f.fixed_lambda = lambda;
    f.fixed_scale = 1.0f;
    FrameImage image;
    FrameStats st = renderer.render(cam, &image, f);
    EXPECT_EQ(st.branch_draws, 0u) << "the tree is not in the view";
    EXPECT_GE(st.shadow_casters[0] + st.shadow_casters[1] + st.shadow_casters[2], 1u);
    double dark = 0.0;
    for (uint32_t y = 0; y < size; ++y)
      for (uint32_t x = 0; x < size; ++x) dark += (lit.pixel(x, y)[0] - image.pixel(x, y)[0]) / 255.0;
    return dark / double(size * size);
  };
  const double full = shadowed(1.0f), pruned = shadowed(0.2f);
  EXPECT_GT(full, 0.02) << "the tree behind the camera casts onto the ground in view";
  {  // With occlusion feedback the receiver mask runs: the ground in view still needs the tree.
    FrameSettings f;
    f.shadows = f.shadow_view = f.occlusion = true;
    FrameImage plain, masked;
    f.receiver_mask = false;
    renderer.render(cam, &plain, f);
    f.receiver_mask = true;
    FrameStats st = renderer.render(cam, &masked, f);
    EXPECT_GE(st.shadow_casters[0] + st.shadow_casters[1] + st.shadow_casters[2], 1u);
    EXPECT_EQ(masked.rgba, plain.rgba) << "the receiver mask dropped a shadow the camera sees";
  }
  EXPECT_LT(pruned, 0.7 * full) << "a fifth of the leaves without compensation casts less shadow";
  for (uint32_t y = size / 2; y < size; ++y)  // the ground, lit everywhere without shadows
    for (uint32_t x = 0; x < size; ++x) ASSERT_EQ(lit.pixel(x, y)[0], 255) << "shadows off: everything lit";
}

// Coverage is light-independent: the mask frames are identical with shadows on and off.
TEST_F(Light, CoverageIsTheSameWithAndWithoutShadows) {
  const uint32_t size = 160;
  Scene s = grove(size);
  Renderer renderer(ctx_, s, size, size, 1);
  CameraDesc cam;
  cam.position = {0.0f, 8.0f, -30.0f};
  cam.target = {0.0f, 5.0f, 0.0f};
  for (PruneMode mode : {PruneMode::full, PruneMode::cook}) {
    FrameSettings f;
    f.mask = true;
    f.prune_mode = mode;
    FrameImage off, on;
    renderer.render(cam, &off, f);
    f.shadows = true;
    renderer.render(cam, &on, f);
    EXPECT_EQ(off.rgba, on.rgba) << prune_mode_name(mode);
    size_t covered = 0;
    for (size_t i = 0; i < on.rgba.size(); i += 4) covered += on.rgba[i] > 0;
    EXPECT_GT(covered, size * size / 20);
  }
  // PR counts (what the bake measures its tables with) alike.
  FrameSettings reference;
  renderer.render_reference(cam, reference);
  FrameSettings test;
  test.prune_mode = PruneMode::fixed;
  test.fixed_lambda = 0.3f;
  test.fixed_scale = 2.0f;
  PrResult without = renderer.compare_with_reference(cam, test);
  test.shadows = true;
  PrResult with = renderer.compare_with_reference(cam, test);
  EXPECT_EQ(without.tp, with.tp);
  EXPECT_EQ(without.fp, with.fp);
  EXPECT_EQ(without.fn, with.fn);
  EXPECT_GT(without.fn + without.fp, 0u) << "the pruned frame differs from full detail";
  // And the shaded frame does change: the shadows are really drawn.
  FrameSettings shaded;
  FrameImage off, on;
  renderer.render(cam, &off, shaded);
  shaded.shadows = true;
  renderer.render(cam, &on, shaded);
  EXPECT_NE(off.rgba, on.rgba);
}

// Sun light through a leaf scatters forward. A wall of opaque leaf cards with the sun behind
// it: seen from its unlit side, looking toward the sun, it is >= 1.5 x as bright as the same
// side seen from 60° off that line.
TEST_F(Light, LeavesScatterTheSunTowardAViewerLookingAtIt) {
  const uint32_t size = 96;
  SceneDesc d = flat_ground(size, size, 100.0f);
  const glm::vec3 sun = glm::normalize(glm::vec3(0.0f, 0.25f, 1.0f));  // behind the wall (+z), low
  d.sky.sun_direction = sun;
  TreeModel wall;
  wall.leaf_card = make_leaf_card(LeafShape::needles);
  const float w = leaf_card_aspect(LeafShape::needles);
  for (int r = 0; r < 8; ++r)
    for (int c = 0; c < 16; ++c) {
      LeafPlacement l;
      l.position = {(float(c) - 7.5f) * w, 2.0f + float(r), 0.0f};
      wall.leaves.push_back(l);
    }
  wall.branches.vertices = {{{0, 5, 1}, {0, 0, -1}, {}}, {{0.1f, 5, 1}, {0, 0, -1}, {}}, {{0, 5.1f, 1}, {0, 0, -1}, {}}};
  wall.branches.indices = {0, 1, 2};
  wall.bounding_sphere = glm::vec4(0.0f, 6.0f, 0.0f, 7.0f);
  d.trees = {TreeDesc{}};
  Scene s = scene_of(std::move(d), {wall});
  Renderer renderer(ctx_, s, size, size, 1);
  auto brightness = [&](float angle_deg) {
    // 10 m from the wall's middle on its unlit side (-z), `angle_deg` off the line to the sun.
    const glm::vec3 middle{0.0f, 6.0f, 0.0f};
    float a = glm::radians(angle_deg);
    glm::vec3 toward_viewer = glm::normalize(-sun);
    glm::vec3 side{std::sin(a), 0.0f, 0.0f};
    CameraDesc cam;
    cam.position = middle + 10.0f * glm::normalize(toward_viewer * std::cos(a) + side);
    cam.target = middle;
    cam.fov_deg = 12.0f;  // the wall's middle only
    FrameSettings f;
    f.shadows = true;
    FrameImage image, mask;
    renderer.render(cam, &image, f);
    f.mask = true;
    renderer.render(cam, &mask, f);
    double sum = 0.0;
    size_t n = 0;
    for (uint32_t y = 0; y < size; ++y)
      for (uint32_t x = 0; x < size; ++x)
        if (mask.pixel(x, y)[0] == 255) {
          const uint8_t* p = image.pixel(x, y);
          sum += 0.2126 * linear(p[0]) + 0.7152 * linear(p[1]) + 0.0722 * linear(p[2]);
          ++n;
        }
    EXPECT_GT(n, size_t(size * size) / 2) << "the wall fills the view at " << angle_deg << "°";
    return n ? sum / double(n) : 0.0;
  };
  const double toward = brightness(0.0f), off_axis = brightness(60.0f);
  EXPECT_GE(toward, 1.5 * off_axis) << "toward the sun " << toward << ", 60° off " << off_axis;
}

// Hills shadow trees: the terrain is drawn into the shadow map. A ridge between a tree and a
// low sun leaves the tree's leaves in shadow that, on flat ground, see the sun.
TEST_F(Light, AHillBetweenTheSunAndATreeShadowsTheTree) {
  const uint32_t size = 128;
  auto tree_visibility = [&](bool ridge) {
    SceneDesc d = flat_ground(size, size, 200.0f);
    d.terrain.resolution = 100;
    d.sky.sun_direction = glm::normalize(glm::vec3(0.0f, 0.35f, 1.0f));  // low, from +z
    d.trees = {TreeDesc{0, 0.0f, -5.0f, 1.0f, 0.0f}};
    Scene s;
    s.desc = d;
    s.terrain = make_terrain(s.desc.terrain);
    if (ridge)  // 30 m high at z = 20, 10 m wide
      for (uint32_t j = 0; j <= s.terrain.desc.resolution; ++j)
        for (uint32_t i = 0; i <= s.terrain.desc.resolution; ++i) {
          float z = -100.0f + 200.0f * float(j) / float(s.terrain.desc.resolution);
          s.terrain.heights[size_t(j) * (s.terrain.desc.resolution + 1) + i] =
              30.0f * std::exp(-(z - 20.0f) * (z - 20.0f) / 50.0f);
        }
    s.models = {broadleaf()};
    s.instances = place_trees(s.desc, s.terrain);
    Renderer renderer(ctx_, s, size, size, 1);
    CameraDesc cam;  // from the side (-x), so that half the crown faces the sun
    cam.position = {-25.0f, 6.0f, -5.0f};
    cam.target = {0.0f, 6.0f, -5.0f};
    FrameSettings f;
    f.shadows = true;
    f.shadow_view = true;
    FrameImage vis, mask;
    renderer.render(cam, &vis, f);
    f.mask = true;
    renderer.render(cam, &mask, f);
    double sum = 0.0;
    size_t n = 0;
    for (uint32_t y = 0; y < size; ++y)
      for (uint32_t x = 0; x < size; ++x)
        if (mask.pixel(x, y)[0] == 255) sum += vis.pixel(x, y)[0] / 255.0, ++n;
    EXPECT_GT(n, 500u);
    return n ? sum / double(n) : 0.0;
  };
  const double flat = tree_visibility(false), behind_ridge = tree_visibility(true);
  EXPECT_GT(flat, 0.25) << "on flat ground the sun's side of the crown is lit";
  EXPECT_LT(behind_ridge, 0.3 * flat) << "behind the ridge the tree is in the hill's shadow";
}

// Trees shadow each other: a tree standing between a low sun and another tree puts the other
// tree's sun side into shadow.
TEST_F(Light, ATreeBetweenTheSunAndAnotherShadowsIt) {
  const uint32_t size = 128;
  auto tree_visibility = [&](bool neighbour) {
    SceneDesc d = flat_ground(size, size, 200.0f);
    d.sky.sun_direction = glm::normalize(glm::vec3(0.0f, 0.3f, 1.0f));  // low, from +z
    d.trees = {TreeDesc{0, 0.0f, 0.0f, 1.0f, 0.0f}};
    if (neighbour) d.trees.push_back(TreeDesc{0, 0.0f, 6.0f, 1.4f, 90.0f});  // nearer the sun, larger
    Scene s = scene_of(std::move(d), {broadleaf()});
    Renderer renderer(ctx_, s, size, size, 1);
    CameraDesc cam;  // from the side (-x), framing the first tree
    cam.position = {-25.0f, 5.0f, -2.0f};
    cam.target = {0.0f, 5.0f, -2.0f};
    cam.fov_deg = 30.0f;
    FrameSettings f;
    f.shadows = true;
    f.shadow_view = true;
    FrameImage vis, mask;
    renderer.render(cam, &vis, f);
    f.mask = true;
    renderer.render(cam, &mask, f);
    // The first tree's half away from the neighbour (z < 0 side of the picture's trees is
    // its own): every tree pixel in the left two thirds of the frame (screen right is +z).
    double sum = 0.0;
    size_t n = 0;
    for (uint32_t y = 0; y < size; ++y)
      for (uint32_t x = 0; x < size * 2 / 3; ++x)
        if (mask.pixel(x, y)[0] == 255) sum += vis.pixel(x, y)[0] / 255.0, ++n;
    EXPECT_GT(n, 300u);
    return n ? sum / double(n) : 0.0;
  };
  const double alone = tree_visibility(false), shaded = tree_visibility(true);
  EXPECT_LT(shaded, 0.75 * alone) << "alone " << alone << ", behind the neighbour " << shaded;
}

// The receiver mask (receiver_mask.comp): trees behind a ridge the camera faces cast only onto
// ground nobody sees, so no cascade draws them, while a tree in front of the ridge keeps its
// shadow; the frame is the same pixel for pixel as without the mask.
TEST_F(Light, CastersWhoseShadowsNobodySeesAreSkipped) {
  const uint32_t size = 128;
  SceneDesc d = flat_ground(size, size, 200.0f);
  d.terrain.resolution = 100;
  d.sky.sun_direction = glm::normalize(glm::vec3(0.3f, 0.8f, -0.6f));  // from -z: shadows fall toward +z
  d.trees = {TreeDesc{0, 0.0f, 4.0f, 1.0f, 0.0f}};  // in front of the ridge
  for (int i = 0; i < 9; ++i)                          // behind it
    d.trees.push_back(TreeDesc{0, float(i % 3) * 10.0f - 10.0f, 40.0f + float(i / 3) * 10.0f, 1.0f, float(i) * 40.0f});
  Scene s;
  s.desc = d;
  s.terrain = make_terrain(s.desc.terrain);
  for (uint32_t j = 0; j <= s.terrain.desc.resolution; ++j)  // 30 m high at z = 20
    for (uint32_t i = 0; i <= s.terrain.desc.resolution; ++i) {
      float z = -100.0f + 200.0f * float(j) / float(s.terrain.desc.resolution);
      s.terrain.heights[size_t(j) * (s.terrain.desc.resolution + 1) + i] = 30.0f * std::exp(-(z - 20.0f) * (z - 20.0f) / 50.0f);
    }
  s.models = {broadleaf()};
  s.instances = place_trees(s.desc, s.terrain);
  CameraDesc cam;
  cam.position = {0.0f, 3.0f, -10.0f};
  cam.target = {0.0f, 8.0f, 20.0f};
  cam.fov_deg = 60.0f;
  auto frame = [&](bool receiver_mask, FrameImage& image) {
    Renderer renderer(ctx_, s, size, size, 1);
    FrameSettings f;
    f.shadows = f.shadow_view = f.occlusion = true;
    f.receiver_mask = receiver_mask;
    renderer.render(cam, nullptr, f);  // the depth the mask is made from
    FrameStats st = renderer.render(cam, &image, f);
    return st.shadow_casters[0] + st.shadow_casters[1] + st.shadow_casters[2];
  };
  FrameImage plain, masked;
  const uint32_t all = frame(false, plain), needed = frame(true, masked);
  EXPECT_GE(all, 10u) << "without the mask every tree in a cascade volume casts";
  EXPECT_GE(needed, 1u) << "the tree in front of the ridge casts onto ground in view";
  EXPECT_LE(needed, 3u) << "the trees behind the ridge cast where nobody looks";
  EXPECT_EQ(masked.rgba, plain.rgba) << "the receiver mask changed the picture";
  size_t dark = 0;
  for (uint32_t y = 0; y < size; ++y)
    for (uint32_t x = 0; x < size; ++x) dark += plain.pixel(x, y)[0] < 128;
  EXPECT_GT(dark, 50u) << "the front tree's shadow is in view";
}

// Seen from above, the ground in view sits off the centre of its cascade's map (the map is
// centred on the view slice, the ground below it lies down-sun of it): every tree's shadow
// there must survive the receiver mask, pixel for pixel.
TEST_F(Light, TheReceiverMaskKeepsEveryShadowSeenFromAbove) {
  const uint32_t size = 128;
  Scene s = grove(size);
  FrameImage plain, masked;
  for (bool receiver_mask : {false, true}) {
    Renderer renderer(ctx_, s, size, size, 1);
    FrameSettings f;
    f.shadows = f.shadow_view = f.occlusion = true;
    f.receiver_mask = receiver_mask;
    renderer.render(top_down(3.0f, -2.0f, 40.0f), nullptr, f);
    renderer.render(top_down(3.0f, -2.0f, 40.0f), receiver_mask ? &masked : &plain, f);
  }
  size_t dark = 0;
  for (uint32_t y = 0; y < size; ++y)
    for (uint32_t x = 0; x < size; ++x) dark += plain.pixel(x, y)[0] < 128;
  EXPECT_GT(dark, size_t(size * size / 20)) << "the grove shades the ground";
  EXPECT_EQ(masked.rgba, plain.rgba) << "the receiver mask dropped a shadow the camera sees";
}

// A leaf reads the shadow map once, at its card's centre (lighting.glsl, leaf_sun_shadow),
// unless the scene asks for per-fragment reads ([render] leaf_shadows = "fragment"). Seen from
// afar (leaves under a pixel) the trees' sun visibility is what the per-fragment reads give;
// seen from near (leaves of a dozen pixels, several texels) only edges crossing a leaf differ:
// close on average and pixel by pixel. Either way not the same frame: the leaves' reads were made.
TEST_F(Light, ALeafReadsTheShadowMapOnce) {
  const uint32_t size = 160;
  Scene once = grove(size), per_fragment = grove(size);
  per_fragment.desc.leaf_shadows_per_fragment = true;
  Renderer r_once(ctx_, once, size, size, 1), r_fragment(ctx_, per_fragment, size, size, 1);
  struct Compared { size_t tree_pixels = 0, differing = 0; double mean_abs = 0.0, mean_bias = 0.0, mean = 0.0; };
  auto compare = [&](glm::vec3 position, glm::vec3 target, float fov) {
    CameraDesc cam;
    cam.position = position;
    cam.target = target;
    cam.fov_deg = fov;
    FrameSettings f;
    f.shadows = f.shadow_view = true;
    FrameImage a_image, b_image, mask;
    r_once.render(cam, &a_image, f);
    r_fragment.render(cam, &b_image, f);
    f.mask = true;
    r_once.render(cam, &mask, f);
    Compared c;
    for (uint32_t y = 0; y < size; ++y)
      for (uint32_t x = 0; x < size; ++x) {
        if (mask.pixel(x, y)[0] != 255) continue;
        const double a = a_image.pixel(x, y)[0] / 255.0, b = b_image.pixel(x, y)[0] / 255.0;
        ++c.tree_pixels;
        c.differing += a != b;
        c.mean_abs += std::abs(a - b);
        c.mean_bias += a - b;
        c.mean += b;
      }
    const double n = double(std::max<size_t>(c.tree_pixels, 1));
    c.mean_abs /= n, c.mean_bias /= n, c.mean /= n;
    std::printf("tree pixels %zu, differing %zu, mean |diff| %.4f, bias %+.4f, mean visibility %.3f\n", c.tree_pixels,
                c.differing, c.mean_abs, c.mean_bias, c.mean);
    return c;
  };
  // From 75 m with 30° of view a pixel spans 0.25 m: the 0.11 m leaves are under half a pixel.
  const Compared far = compare({60.0f, 30.0f, 40.0f}, {0.0f, 4.0f, 0.0f}, 30.0f);  // from the shaded side
  EXPECT_GT(far.tree_pixels, 1500u);
  EXPECT_GT(far.mean, 0.2);
  EXPECT_LT(far.mean, 0.9) << "part of the crowns in the shadow of others";
  EXPECT_GT(far.differing, 0u) << "the leaves read the map once";
  EXPECT_LT(far.mean_abs, 0.03) << "once a leaf against per fragment, pixel by pixel";
  EXPECT_LT(std::abs(far.mean_bias), 0.01) << "once a leaf against per fragment, on average";
  // 6 m from the nearest crown with 40° of view a pixel spans about 2 cm: leaves of 5 px and more.
  const Compared near = compare({-9.0f, 6.0f, -16.0f}, {-9.0f, 5.0f, -9.0f}, 40.0f);
  EXPECT_GT(near.tree_pixels, size * size / 4);
  EXPECT_GT(near.differing, 0u);
  EXPECT_LT(near.mean_abs, 0.08);
  EXPECT_LT(std::abs(near.mean_bias), 0.02);
}
