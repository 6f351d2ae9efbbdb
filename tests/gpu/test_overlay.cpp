// The debug overlay pass (engine/render/pyramid_overlay_pass.h) on the Vulkan device,
// validation layer on: the depth pyramid that the occlusion test reads, drawn in grey over
// the top-right quarter of the frame and nowhere else; only with occlusion on.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <set>

#include "engine/render/renderer.h"
#include "tests/gpu/gpu_scenes.h"
#include "tests/gpu/validated_gpu_test.h"

using namespace forest;
using namespace forest::test;

namespace {

class OverlayTest : public ValidatedGpuTest {};

constexpr uint32_t kWidth = 160, kHeight = 120;

// One broadleaf in front of the camera on flat ground: nothing is hidden, so occlusion
// changes nothing between frames and two renders of the view are identical.
Scene one_tree() {
  SceneDesc desc = flat_ground(kWidth, kHeight, 200.0f);
  desc.trees = {{0, 0.0f, 0.0f, 1.0f, 0.0f}};
  desc.camera.position = {0.0f, 5.0f, -16.0f};
  desc.camera.target = {0.0f, 5.0f, 0.0f};
  return scene_of(std::move(desc), {broadleaf()});
}

// The second of two frames of one view (the first builds the depth pyramid).
FrameImage second_frame(vk::Context& ctx, const Scene& scene, const FrameSettings& settings) {
  Renderer r(ctx, scene, kWidth, kHeight);
  FrameSettings first = settings;
  first.pyramid_overlay = false;
  r.render(scene.desc.camera, nullptr, first);
  FrameImage image;
  r.render(scene.desc.camera, &image, settings);
  return image;
}

bool inside(const VkRect2D& r, uint32_t x, uint32_t y) {
  return x >= uint32_t(r.offset.x) && x < uint32_t(r.offset.x) + r.extent.width && y >= uint32_t(r.offset.y) &&
         y < uint32_t(r.offset.y) + r.extent.height;
}

}  // namespace

TEST_F(OverlayTest, PyramidOverlayCoversOnlyItsQuarterAndShowsDepth) {
  Scene scene = one_tree();
  FrameSettings plain;
  plain.occlusion = true;
  FrameSettings overlay = plain;
  overlay.pyramid_overlay = true;
  FrameImage a = second_frame(ctx_, scene, plain), b = second_frame(ctx_, scene, overlay);
  const VkRect2D rect = pyramid_overlay_rect({kWidth, kHeight});
  ASSERT_EQ(rect.extent.width, kWidth / 2);
  ASSERT_EQ(rect.offset.x, int32_t(kWidth / 2));
  ASSERT_EQ(rect.offset.y, 0);
  size_t outside_changed = 0, inside_changed = 0, not_grey = 0;
  std::set<int> greys;
  for (uint32_t y = 0; y < kHeight; ++y)
    for (uint32_t x = 0; x < kWidth; ++x) {
      const uint8_t *pa = a.pixel(x, y), *pb = b.pixel(x, y);
      bool changed = std::memcmp(pa, pb, 3) != 0;
      if (!inside(rect, x, y)) {
        outside_changed += changed;
        continue;
      }
      inside_changed += changed;
      not_grey += !(pb[0] == pb[1] && pb[1] == pb[2]);
      greys.insert(pb[0]);
    }
  EXPECT_EQ(outside_changed, 0u) << "the overlay drew outside its quarter";
  EXPECT_GT(inside_changed, size_t(rect.extent.width) * rect.extent.height / 2) << "the overlay is missing";
  EXPECT_EQ(not_grey, 0u);
  // Sky (the far plane) is black; the ground and the tree are nearer, so lighter.
  ASSERT_FALSE(greys.empty());
  EXPECT_EQ(*greys.begin(), 0) << "no far-plane texel";
  EXPECT_GT(*greys.rbegin(), 100) << "nothing near";
  EXPECT_GE(greys.size(), 8u) << "depth should show as a range of greys";
}

TEST_F(OverlayTest, NoOverlayWithoutOcclusion) {
  Scene scene = one_tree();
  FrameSettings plain;  // occlusion off: the pyramid holds nothing to show
  FrameSettings overlay = plain;
  overlay.pyramid_overlay = true;
  FrameImage a = second_frame(ctx_, scene, plain), b = second_frame(ctx_, scene, overlay);
  EXPECT_EQ(a.rgba, b.rgba);
}
