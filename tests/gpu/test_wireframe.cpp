// The wireframe view of `forest walk` (FrameSettings::wireframe): same scene, same culling,
// triangle edges only, so the sky drawn first shows through the terrain.
#include <gtest/gtest.h>

#include "engine/render/renderer.h"
#include "engine/scene/scene.h"

using namespace forest;

namespace {

const std::string kSource = FOREST_SOURCE_DIR;

bool is_sky(const uint8_t* p) { return p[2] > p[0] && p[2] >= p[1] && p[2] > 120; }

size_t sky_pixels_in_lower_half(const FrameImage& img) {
  size_t n = 0;
  for (uint32_t y = img.height / 2 + 8; y < img.height; ++y)
    for (uint32_t x = 0; x < img.width; ++x) n += is_sky(img.pixel(x, y));
  return n;
}

}  // namespace

TEST(GpuWireframe, EdgesOnlyShowSkyThroughTerrainWithSameCulling) {
  vk::Context ctx;
  vk::ContextOptions options;
  options.validation = true;
  vk::create_context(ctx, options);
  if (!ctx.fill_mode_non_solid) {
    vk::destroy_context(ctx);
    GTEST_SKIP() << "device lacks fillModeNonSolid";
  }
  {
    SceneDesc desc = parse_scene_text(R"(
[render]
width = 128
height = 96
samples = 1
[camera]
position = [0, 6, -24]
target = [0, 4, 0]
[terrain]
size = 200
resolution = 24
height = 1.0
[[species]]
preset = "species/fig2_1.toml"
[[tree]]
species = 0
x = 0
z = 0
)",
                                      "wire.toml", kSource + "/scenes");
    Scene scene = build_scene(desc);
    Renderer renderer(ctx, scene, desc.width, desc.height, desc.samples);
    ASSERT_TRUE(renderer.has_wireframe());
    FrameImage filled, wire;
    FrameSettings settings = scene_frame_settings(desc);
    FrameStats a = renderer.render(desc.camera, &filled, settings);
    settings.wireframe = true;
    FrameStats b = renderer.render(desc.camera, &wire, settings);
    EXPECT_EQ(a.branch_draws, b.branch_draws);
    EXPECT_EQ(a.leaves_drawn, b.leaves_drawn);
    const size_t lower = size_t(desc.width) * (desc.height / 2 - 8);
    EXPECT_LT(sky_pixels_in_lower_half(filled), lower / 50);      // solid ground
    EXPECT_GT(sky_pixels_in_lower_half(wire), lower / 2);         // mostly sky between edges
    EXPECT_LT(sky_pixels_in_lower_half(wire), lower - lower / 50);  // but the edges are drawn
  }
  vk::destroy_context(ctx);
  EXPECT_EQ(ctx.validation_messages.load(), 0u) << ctx.last_validation_message;
}
