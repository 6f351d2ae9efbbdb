// `forest walk` in a real window: Xvfb (xvfb-run) + the device's Vulkan driver (lavapipe in
// CI), validation layer on. Scripted runs (--frames, --fly, --resize-at) exercise the
// swapchain, its recreation, the present step and the HUD; the screenshot is read back from
// the swapchain image, so it shows what the window showed.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "engine/present/image_io.h"
#include "tests/cli/cli_run.h"

namespace fs = std::filesystem;
using namespace forest::test;

namespace {

// A light scene (8 small trees, 320x200, no MSAA) so 30 lavapipe frames stay cheap; the
// camera looks a little up so sky shows below the HUD panel.
std::string light_scene(const std::string& view) {
  return "[render]\nwidth = 320\nheight = 200\nsamples = 1\nlod_error_pixels = 4\nview = \"" + view + "\"\n"
         "[camera]\nposition = [0, 6, -30]\ntarget = [0, 9, 0]\nfov = 50\n"
         "[terrain]\nsize = 120\nresolution = 16\nheight = 3\nseed = 3\n"
         "[[species]]\npreset = \"" + kSourceDir + "/scenes/species/fig2_1.toml\"\nseed = 1\n"
         "[placement]\ncount = 8\nseed = 7\nmin_spacing = 5\nradius = 14\n";
}

class WalkTest : public CliDirTest {
 protected:
  void SetUp() override {
    if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0)
      GTEST_SKIP() << "xvfb-run is missing (apt-get install xvfb; scripts/test.sh installs it)";
    CliDirTest::SetUp();
  }
  int run(const std::string& args, bool window = true, const std::string& prefix = "") {
    Result r = run_captured(prefix + (window ? "xvfb-run -a " : "") + forest_command(args), dir_);
    out_ = r.out;
    err_ = r.err;
    return r.code;
  }
  std::string out_, err_;
};

}  // namespace

// Fly, resize at frame 10, screenshot the last of 30 frames; λ view so classes are colors:
// sky blue, terrain green, trees at λ = 1 red (Fig 7.15 colors), HUD panel dark grey.
TEST_F(WalkTest, ScriptedWalkResizesAndShowsSkyTerrainTreesAndHud) {
  fs::path scene = dir_ / "walk.toml";
  std::ofstream(scene) << light_scene("lambda");
  fs::path shot = dir_ / "x.png";
  int code = run("walk '" + scene.string() + "' --frames 30 --fly --resize-at 10 --screenshot '" + shot.string() +
                 "' --validate");
  ASSERT_EQ(code, 0) << err_;
  EXPECT_EQ(err_.find("validation"), std::string::npos) << err_;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(out_, m, std::regex("(\\d+) frames .* swapchain created (\\d+) time"))) << out_;
  EXPECT_EQ(m[1], "30");
  EXPECT_GE(std::stoi(m[2]), 2) << "the resize must recreate the swapchain";

  forest::FrameImage img = forest::read_image(shot);
  // The window was resized to 3/4 of 320x200 and the screenshot is the window's image.
  EXPECT_EQ(img.width, 240u);
  EXPECT_EQ(img.height, 150u);
  size_t sky = 0, terrain = 0, tree = 0, hud = 0;
  for (uint32_t y = 0; y < img.height; ++y)
    for (uint32_t x = 0; x < img.width; ++x) {
      const uint8_t* p = img.pixel(x, y);
      int r = p[0], g = p[1], b = p[2];
      if (r == 18 && g == 22 && b == 26) ++hud;
      else if (b > 150 && b > r + 12 && b > g) ++sky;  // the tone map pales the horizon a little
      else if (g > r + 10 && g > b + 10) ++terrain;
      else if (r > g + 40 && r > b + 40) ++tree;
    }
  const size_t n = size_t(img.width) * img.height;
  EXPECT_GT(sky, n / 20) << "sky";
  EXPECT_GT(terrain, n / 20) << "terrain";
  EXPECT_GT(tree, 20u) << "trees (red in the lambda view)";
  EXPECT_GT(hud, n / 50) << "HUD panel";
  EXPECT_LT(hud, n / 2) << "HUD panel";
}

// Without moving and without the HUD, the window shows exactly what `forest render` writes:
// both present paths copy the renderer's image 1:1 at the same size (the blit sRGB to sRGB,
// the copy pass by sampling texel centers and re-encoding).
TEST_F(WalkTest, UntouchedFrameEqualsOffscreenRenderByBlitAndByCopyPass) {
  fs::path scene = dir_ / "walk.toml";
  std::ofstream(scene) << light_scene("shaded");
  ASSERT_EQ(run("render '" + scene.string() + "' --out '" + (dir_ / "r.png").string() + "'", false), 0) << err_;
  forest::FrameImage r = forest::read_image(dir_ / "r.png");
  for (const char* present : {"blit", "pass"}) {
    SCOPED_TRACE(present);
    fs::path shot = dir_ / (std::string(present) + ".png");
    ASSERT_EQ(run("walk '" + scene.string() + "' --frames 2 --no-hud --present " + present + " --screenshot '" +
                  shot.string() + "' --validate"),
              0)
        << err_;
    forest::FrameImage w = forest::read_image(shot);
    ASSERT_EQ(w.width, r.width);
    ASSERT_EQ(w.height, r.height);
    size_t differ = 0;
    for (size_t i = 0; i < w.rgba.size(); i += 4)
      differ += w.rgba[i] != r.rgba[i] || w.rgba[i + 1] != r.rgba[i + 1] || w.rgba[i + 2] != r.rgba[i + 2];
    EXPECT_EQ(differ, 0u);
  }
}

TEST_F(WalkTest, BadSceneExitsTwoBeforeOpeningAWindow) {
  fs::path scene = dir_ / "bad.toml";
  std::ofstream(scene) << "[render]\nwidth = -3\n";
  EXPECT_EQ(run("walk '" + scene.string() + "' --frames 1", false), 2);
  EXPECT_NE(err_.find("render.width"), std::string::npos) << err_;
  EXPECT_EQ(lines(err_), 1u) << err_;
}

TEST_F(WalkTest, NoDisplayIsOneClearLine) {
  fs::path scene = dir_ / "walk.toml";
  std::ofstream(scene) << light_scene("shaded");
  EXPECT_EQ(run("walk '" + scene.string() + "' --frames 1 --screenshot '" + (dir_ / "x.png").string() + "'",
                false, "env -u DISPLAY -u WAYLAND_DISPLAY "),
            1);
  EXPECT_NE(err_.find("cannot open a window"), std::string::npos) << err_;
  EXPECT_EQ(lines(err_), 1u) << err_;
  EXPECT_FALSE(fs::exists(dir_ / "x.png"));
}

// --play starts the scene's camera path at once: after N scripted frames (1/30 s each) the
// window shows what `forest render --path NAME --time N/30` writes, up to the last bits of
// the accumulated time. A scene without a path is an input error before any window opens.
TEST_F(WalkTest, PlayFollowsTheCameraPathLikeRender) {
  fs::path scene = dir_ / "path.toml";
  std::ofstream(scene) << light_scene("shaded")
                       << "[[path]]\nname = \"orbit\"\nfps = 30\n"
                          "[[path.key]]\ntime = 0\nposition = [0, 6, -30]\ntarget = [0, 9, 0]\n"
                          "[[path.key]]\ntime = 2\nposition = [30, 8, 0]\ntarget = [0, 9, 0]\n";
  ASSERT_EQ(run("render '" + scene.string() + "' --path orbit --time 0.5 --out '" + (dir_ / "r.png").string() + "'",
                false),
            0)
      << err_;
  ASSERT_EQ(run("walk '" + scene.string() + "' --play --frames 15 --no-hud --screenshot '" +
                (dir_ / "w.png").string() + "' --validate"),
            0)
      << err_;
  forest::FrameImage r = forest::read_image(dir_ / "r.png"), w = forest::read_image(dir_ / "w.png");
  ASSERT_EQ(w.rgba.size(), r.rgba.size());
  size_t differ = 0;
  for (size_t i = 0; i < w.rgba.size(); i += 4)
    differ += std::abs(int(w.rgba[i]) - int(r.rgba[i])) + std::abs(int(w.rgba[i + 1]) - int(r.rgba[i + 1])) > 24;
  EXPECT_LT(differ, w.rgba.size() / 4 / 100) << "more than 1 % of the pixels differ";

  fs::path no_path = dir_ / "nopath.toml";
  std::ofstream(no_path) << light_scene("shaded");
  EXPECT_EQ(run("walk '" + no_path.string() + "' --play --frames 2", false), 2);
  EXPECT_NE(err_.find("--play"), std::string::npos) << err_;
}
