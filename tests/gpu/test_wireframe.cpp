// The wireframe view of `forest walk` (FrameSettings::wireframe): same scene, same culling,
// triangle edges only, so the sky drawn first shows through the terrain.
#include <gtest/gtest.h>

#include "engine/render/renderer.h"
#include "engine/scene/scene.h"
#include "tests/gpu/gpu_scenes.h"
#include "tests/gpu/validated_gpu_test.h"

using namespace forest;
using namespace forest::test;

namespace {

class GpuWireframe : public ValidatedGpuTest {};

bool is_sky(const uint8_t* p) { return p[2] > p[0] && p[2] >= p[1] && p[2] > 120; }

size_t sky_pixels_in_lower_half(const FrameImage& img) {
  size_t n = 0;
  for (uint32_t y = img.height / 2 + 8; y < img.height; ++y)
    for (uint32_t x = 0; x < img.width; ++x) n += is_sky(img.pixel(x, y));
  return n;
}

}  // namespace

TEST_F(GpuWireframe, EdgesOnlyShowSkyThroughTerrainWithSameCulling) {
  if (!ctx_.fill_mode_non_solid) GTEST_SKIP() << "device lacks fillModeNonSolid";
  SceneDesc desc = parse_scene(SceneText{.width = 128,
                                         .height = 96,
                                         .target = {0.0f, 4.0f, 0.0f},
                                         .fov = std::nullopt,
                                         .terrain_resolution = 24,
                                         .terrain_seed = std::nullopt,
                                         .species = "fig2_1",
                                         .species_seed = std::nullopt,
                                         .extra = "[[tree]]\nspecies = 0\nx = 0\nz = 0\n"}
                                   .str(),
                               "wire.toml");
  Scene scene = build_scene(desc);
  Renderer renderer(ctx_, scene, desc.width, desc.height, desc.samples);
  ASSERT_TRUE(renderer.has_wireframe());
  FrameImage filled, wire;
  FrameSettings settings = scene_frame_settings(desc);
  FrameStats a = renderer.render(desc.camera, &filled, settings);
  settings.wireframe = true;
  FrameStats b = renderer.render(desc.camera, &wire, settings);
  EXPECT_EQ(a.branch_draws, b.branch_draws);
  EXPECT_EQ(a.leaves_drawn, b.leaves_drawn);
  const size_t lower = size_t(desc.width) * (desc.height / 2 - 8);
  EXPECT_LT(sky_pixels_in_lower_half(filled), lower / 50);        // solid ground
  EXPECT_GT(sky_pixels_in_lower_half(wire), lower / 2);           // mostly sky between edges
  EXPECT_LT(sky_pixels_in_lower_half(wire), lower - lower / 50);  // but the edges are drawn
}
