// PR regression images: canonical views of the test scenes rendered in each prune mode and
// against full detail; Q must stay at or above tests/regression/thresholds.toml. A failing
// check keeps the reference and test coverage and the Fig 7.1 tp/fp/fn picture in
// build/regression-artifacts/ (the path is printed).
#include <gtest/gtest.h>

#include <filesystem>
#include <map>

#include "bench/bench_run.h"
#include "engine/tools/bake/species_cache.h"
#include "engine/present/image_io.h"
#include "engine/tools/report/pr_image.h"
#include "engine/scene/scene.h"
#include "generators/core/toml_reader.h"

using namespace forest;
namespace fs = std::filesystem;

namespace {

const fs::path kRegression = fs::path(FOREST_SOURCE_DIR) / "tests" / "regression";
const fs::path kBinary = FOREST_BINARY_DIR;

struct Check {
  std::string scene, view, mode;
  double min_q = 1.0;
};

std::vector<Check> load_checks() {
  TomlDocument doc = TomlDocument::load(kRegression / "thresholds.toml");
  std::vector<Check> checks;
  for (const TomlTable& c : doc.root().tables("check")) {
    c.check_keys({"scene", "view", "mode", "min_q"});
    checks.push_back({c.string("scene"), c.string("view"), c.string("mode"), c.number("min_q", 0.0, 1.0)});
  }
  return checks;
}

CameraDesc view_camera(const SceneDesc& desc, const std::string& view) {
  if (view == "camera") return desc.camera;
  size_t at = view.find('@');
  const CameraPath* path = at == std::string::npos ? nullptr : find_path(desc, view.substr(0, at));
  if (!path) throw std::runtime_error("thresholds.toml: bad view '" + view + "'");
  return camera_at(*path, path->keys.front().time + float(std::stoi(view.substr(at + 1))) / path->fps, desc.camera);
}

}  // namespace

TEST(Regression, PrunedViewsKeepTheirQuality) {
  std::vector<Check> checks = load_checks();
  ASSERT_FALSE(checks.empty());
  vk::Context ctx;
  vk::ContextOptions options;
  options.validation = true;
  vk::create_context(ctx, options);
  {
    std::map<std::string, Scene> scenes;
    for (const Check& c : checks) {
      SCOPED_TRACE(c.scene + " " + c.view + " " + c.mode);
      auto mode = bench_mode(c.mode);
      ASSERT_TRUE(mode && c.mode != "full" && mode->priority.empty()) << "unknown or unsupported mode";
      if (!scenes.count(c.scene)) {
        SceneBuildOptions build;
        build.species = cached_species_source({kBinary / "test-cache", &ctx, {}});
        scenes.emplace(c.scene, build_scene(load_scene_file(kRegression / c.scene), build));
      }
      const Scene& scene = scenes.at(c.scene);
      CameraDesc camera = view_camera(scene.desc, c.view);
      Renderer test(ctx, scene, scene.desc.width, scene.desc.height, scene.desc.samples);
      Renderer reference(ctx, scene, scene.desc.width, scene.desc.height, scene.desc.samples);
      FrameSettings full, pruned;
      full.mask = pruned.mask = true;
      pruned.prune_mode = mode->prune_mode;
      pruned.occlusion = mode->occlusion;
      // Occlusion feeds back from frame to frame: judge the steady state from this camera.
      for (int i = 0; mode->occlusion && i < 4; ++i) test.render(camera, nullptr, pruned);
      FrameImage ref_image, test_image, diff;
      reference.render(camera, &ref_image, full);
      test.render(camera, &test_image, pruned);
      PrResult pr = compare_coverage(ref_image, test_image, &diff);
      double q = pr.quality();
      std::printf("regression %s %s %s: P %.4f R %.4f Q %.4f (min %.4f)\n", c.scene.c_str(), c.view.c_str(),
                  c.mode.c_str(), pr.precision(), pr.recall(), q, c.min_q);
      EXPECT_GT(pr.tp, 200u) << "the view shows almost no tree: a broken scene, not a quality check";
      if (q < c.min_q) {
        fs::path dir = kBinary / "regression-artifacts";
        fs::create_directories(dir);
        std::string stem = fs::path(c.scene).stem().string() + "_" + c.view + "_" + c.mode;
        for (char& ch : stem)
          if (ch == '@') ch = '-';
        write_image(ref_image, dir / (stem + "_reference.png"));
        write_image(test_image, dir / (stem + "_test.png"));
        write_image(diff, dir / (stem + "_tpfpfn.png"));
        ADD_FAILURE() << "Q " << q << " < " << c.min_q << "; images in " << (dir / stem).string() << "_*.png";
      }
    }
  }
  vk::destroy_context(ctx);
  EXPECT_EQ(ctx.validation_messages.load(), 0u) << "last: " << ctx.last_validation_message;
}
