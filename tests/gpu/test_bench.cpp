// forest bench on the device: a path played twice gives the same per-frame counts, pruning
// draws less than full detail along it, and the throughput probe draws what it claims.
#include <gtest/gtest.h>

#include "bench/bench_run.h"
#include "bench/bench_throughput.h"
#include "engine/tools/bake/species_cache.h"
#include "engine/scene/scene.h"
#include "tests/gpu/validated_gpu_test.h"

using namespace forest;

namespace {

const std::filesystem::path kSource = FOREST_SOURCE_DIR;
const std::filesystem::path kBinary = FOREST_BINARY_DIR;

class BenchTest : public ValidatedGpuTest {
 protected:
  Scene grove() {
    SceneBuildOptions build;
    build.species = cached_species_source({kBinary / "test-cache", &ctx_, {}});
    return build_scene(load_scene_file(kSource / "tests/regression/grove.toml"), build);
  }
};

}  // namespace

TEST_F(BenchTest, PathPlaysDeterministicallyAndPrunes) {
  Scene scene = grove();
  const CameraPath& path = *find_path(scene.desc, "orbit");
  BenchPlayOptions o;
  o.width = 96, o.height = 64;
  o.frames = bench_frames(path, 2, 0);  // fps 4 over 1 s: frames 0, 2, 4
  ASSERT_EQ(o.frames, (std::vector<uint32_t>{0, 2, 4}));
  o.pr_every = 2;
  for (const char* name : {"opt-occl", "opt"}) {
    SCOPED_TRACE(name);
    BenchMode mode = *bench_mode(name);
    std::vector<BenchFrame> a = play_bench_path(ctx_, scene, path, mode, o);
    std::vector<BenchFrame> b = play_bench_path(ctx_, scene, path, mode, o);
    ASSERT_EQ(a.size(), 3u);
    // The warm-up draw before the first recorded frame leaves occlusion no history: that
    // frame is a cut and saves nothing.
    EXPECT_EQ(a[0].stats.camera_cut, mode.occlusion);
    EXPECT_EQ(a[0].stats.leaves_saved, 0u);
    for (size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].stats.leaves_drawn, b[i].stats.leaves_drawn) << i;
      EXPECT_EQ(a[i].tree_triangles, b[i].tree_triangles) << i;
      EXPECT_EQ(a[i].stats.branch_draws, b[i].stats.branch_draws) << i;
      EXPECT_EQ(a[i].has_pr, i % 2 == 0) << i;
      EXPECT_EQ(a[i].pr.tp, b[i].pr.tp) << i;
    }
  }
  std::vector<BenchFrame> full = play_bench_path(ctx_, scene, path, *bench_mode("full"), o);
  std::vector<BenchFrame> opt = play_bench_path(ctx_, scene, path, *bench_mode("opt"), o);
  for (size_t i = 0; i < full.size(); ++i) {
    EXPECT_LT(opt[i].stats.leaves_drawn, full[i].stats.leaves_drawn) << i;
    EXPECT_GT(opt[i].tree_triangles, 0u);
  }
  EXPECT_DOUBLE_EQ(full[0].pr.quality(), 1.0);  // full detail against itself
  EXPECT_LT(opt[0].pr.quality(), 1.0);

  // References shared by the modes of one run (forest bench): rendered once per PR frame,
  // by the first mode, and every mode then measures what it measured alone.
  std::map<uint32_t, FrameImage> references;
  o.references = &references;
  std::vector<BenchFrame> opt_shared = play_bench_path(ctx_, scene, path, *bench_mode("opt"), o);
  EXPECT_EQ(references.size(), 2u);  // frames 0 and 4
  std::vector<BenchFrame> full_shared = play_bench_path(ctx_, scene, path, *bench_mode("full"), o);
  EXPECT_EQ(references.size(), 2u);
  for (size_t i = 0; i < opt.size(); i += 2) {
    EXPECT_EQ(opt_shared[i].pr.tp, opt[i].pr.tp) << i;
    EXPECT_EQ(opt_shared[i].pr.fp, opt[i].pr.fp) << i;
    EXPECT_EQ(opt_shared[i].pr.fn, opt[i].pr.fn) << i;
    EXPECT_DOUBLE_EQ(full_shared[i].pr.quality(), 1.0) << i;
  }
}

TEST_F(BenchTest, ThroughputProbeDrawsEveryTriangle) {
  ThroughputOptions o;
  o.width = 64, o.height = 48;
  o.grid = 16, o.instances = 9, o.frames = 1;
  ThroughputResult r = measure_triangle_throughput(ctx_, o);
  uint64_t sheet = 2ull * 16 * 16 * 9;
  EXPECT_GE(r.triangles_per_frame, sheet);           // every sheet drawn (no culling, LOD0)
  EXPECT_LE(r.triangles_per_frame, sheet + 9 + 64);  // + one leaf each, terrain and sky
  EXPECT_GT(r.draw_ms, 0.0);
  EXPECT_GT(r.triangles_per_second(), 0.0);
}
