// forest bench as a user runs it: bad input is one line and exit 2 with nothing written; a
// short run writes the CSV per mode, the JSON summary against Cook and the two plots.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/cli/cli_run.h"

namespace fs = std::filesystem;
using namespace forest::test;

namespace {

class BenchCliTest : public CliDirTest {
 protected:
  void SetUp() override {
    CliDirTest::SetUp();
    fs::create_directories(dir_ / "out");
  }
  int run(const std::string& args) {
    Result r = run_captured(forest_command("bench " + args), dir_);
    out_ = r.out, err_ = r.err;
    return r.code;
  }
  // Two fig2_1 trees (the tiny scene's species and bake: a species-cache hit) and a path.
  fs::path scene(bool with_path = true) {
    std::string text = "[render]\nwidth = 64\nheight = 48\nsamples = 1\n"
                       "[camera]\nposition = [0, 6, -30]\ntarget = [0, 4, 0]\n"
                       "[terrain]\nsize = 100\nresolution = 8\nheight = 0\n"
                       "[bake]\nviews = 2\nresolution = 64\nimpostor = false\n"
                       "[[species]]\npreset = \"" + kSourceDir + "/scenes/species/fig2_1.toml\"\nseed = 1\n"
                       "[[tree]]\nspecies = 0\nx = -3\nz = 0\n[[tree]]\nspecies = 0\nx = 4\nz = 6\n";
    if (with_path)
      text += "[[path]]\nname = \"dolly\"\nfps = 2\n"
              "[[path.key]]\ntime = 0\nposition = [0, 6, -40]\ntarget = [0, 4, 0]\n"
              "[[path.key]]\ntime = 1\nposition = [0, 6, -20]\ntarget = [0, 4, 0]\n";
    fs::path p = dir_ / (with_path ? "scene.toml" : "nopath.toml");
    std::ofstream(p) << text;
    return p;
  }
  bool out_empty() const { return fs::is_empty(dir_ / "out"); }
  std::string out_, err_;
};

}  // namespace

TEST_F(BenchCliTest, BadInputIsOneLineExitTwoNothingWritten) {
  std::string out = " --out '" + (dir_ / "out").string() + "'";
  struct Case {
    std::string args, needle;
  };
  std::vector<Case> cases = {
      {"'" + scene().string() + "' --modes cook,fast" + out, "fast"},
      {"'" + scene().string() + "' --path nowhere" + out, "nowhere"},
      {"'" + scene(false).string() + "'" + out, "no [[path]]"},
      {"'" + scene().string() + "' --every 0" + out, "--every"},
      {"'" + scene().string() + "' --frames -3" + out, "--frames"},
      {"'" + scene().string() + "' --width nan" + out, "--width"},
      {"'" + scene().string() + "' --out '" + scene().string() + "'", "is not a folder"},
      {"'" + (dir_ / "absent.toml").string() + "'" + out, "absent.toml"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args);
    EXPECT_EQ(run(c.args), 2) << err_;
    EXPECT_EQ(lines(err_), 1u) << err_;
    EXPECT_NE(err_.find(c.needle), std::string::npos) << err_;
    EXPECT_TRUE(out_empty());
  }
}

TEST_F(BenchCliTest, WritesCsvJsonAndPlotsAgainstCook) {
  // --out names a folder that does not exist yet: the bench makes it.
  const fs::path out = dir_ / "made" / "here";
  ASSERT_EQ(run("'" + scene().string() + "' --modes full,cook,opt --pr-every 1 --tree-pr 2 --probe-instances 2 --out '" + out.string() + "'"),
            0)
      << err_;
  for (const char* f : {"summary.json", "frames_full.csv", "frames_cook.csv", "frames_opt.csv", "triangles.png",
                        "frame_time.png"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  // fps 2 over 1 s: frames 0, 1, 2 (header + 3 rows), each with P, R, Q.
  std::string csv = slurp(out / "frames_opt.csv");
  EXPECT_EQ(lines(csv), 4u) << csv;
  auto j = nlohmann::json::parse(slurp(out / "summary.json"));
  EXPECT_FALSE(j["device"].get<std::string>().empty());
  EXPECT_EQ(j["resolution"][0], 64);
  EXPECT_EQ(j["frames"], 3);
  EXPECT_GT(j["throughput_probe"]["triangles_per_second"].get<double>(), 0.0);
  auto& m = j["modes"];
  EXPECT_DOUBLE_EQ(m["cook"]["geometry_vs_cook"].get<double>(), 1.0);
  // Full detail is the reference of PR: Q = 1 exactly; pruning draws less than full detail.
  EXPECT_DOUBLE_EQ(m["full"]["q"].get<double>(), 1.0);
  EXPECT_LT(m["cook"]["tree_triangles"].get<double>(), m["full"]["tree_triangles"].get<double>());
  EXPECT_LT(m["opt"]["tree_triangles"].get<double>(), m["full"]["tree_triangles"].get<double>());
  EXPECT_GT(m["opt"]["q"].get<double>(), 0.5);
  EXPECT_LE(m["opt"]["q"].get<double>(), 1.0);
  // --tree-pr: the first mode is played once unrecorded first (cmd_bench.cpp), and what is
  // recorded is one pass: 3 frames, each tree alone at full detail exactly its reference.
  EXPECT_EQ(lines(slurp(out / "frames_full.csv")), 4u);
  EXPECT_EQ(m["full"]["tree_pr"]["frames"], 3);
  EXPECT_DOUBLE_EQ(m["full"]["tree_pr"]["mean_q"].get<double>(), 1.0);
  EXPECT_EQ(m["opt"]["tree_pr"]["frames"], 3);
}
