// `forest measure`: one line per metric, the same numbers in --json, the leaf masks with
// --masks, the same coverage and depth from a preset and from its .glb, and bad input → exit
// code 2 with one line and no output file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/present/image_io.h"
#include "tests/cli/cli_run.h"

namespace fs = std::filesystem;
using namespace forest::test;

namespace {

const std::string kPreset = kSourceDir + "/scenes/species/fig2_1.toml";

class CliMeasure : public CliDirTest {
 protected:
  Result run(const std::string& args) { return run_captured(forest_command("measure " + args), dir_); }
  std::string path(const std::string& name) const { return "'" + (dir_ / name).string() + "'"; }
  void expect_one_line_error(const Result& r, const std::string& what) {
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find(what), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "m.json"));
  }
};

// The value after "key " on its line of `out`, or NaN.
double value_of(const std::string& out, const std::string& key) {
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(key + " ", 0) == 0) return std::stod(line.substr(key.size() + 1));
  return std::nan("");
}

}  // namespace

TEST_F(CliMeasure, PresetGivesEveryMetricAndTheSameJson) {
  fs::create_directory(dir_ / "masks");
  Result r = run("--species '" + kPreset + "' --seed 3 --resolution 128 --json " + path("m.json") + " --masks " +
                 path("masks"));
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* key : {"leaves", "height_m", "crown_width_m", "crown_width_over_height", "clear_bole_over_height",
                          "trunk_fraction", "single_leader", "lowest_leaf_over_height", "coverage_az000", "coverage_az090", "coverage_az180",
                          "coverage_az270", "coverage_min", "depth_m", "depth_over_half_width", "depth_histogram"})
    EXPECT_NE(r.out.find(std::string(key) + " "), std::string::npos) << key << "\n" << r.out;
  nlohmann::json j = nlohmann::json::parse(slurp(dir_ / "m.json"));
  EXPECT_EQ(j["seed"], 3);
  EXPECT_EQ(j["species"], "fig2_1");
  EXPECT_GT(j["leaves"].get<int>(), 100);
  EXPECT_EQ(j["leaves"].get<double>(), value_of(r.out, "leaves"));
  EXPECT_NEAR(j["habit"]["height_m"].get<double>(), value_of(r.out, "height_m"), 0.006);
  EXPECT_GT(j["habit"]["height_m"].get<double>(), 0.5);
  ASSERT_EQ(j["coverage"]["views"].size(), 4u);
  double smallest = 1.0;
  for (const auto& v : j["coverage"]["views"]) {
    double c = v["coverage"].get<double>();
    EXPECT_GT(c, 0.0);
    EXPECT_LE(c, 1.0);
    smallest = std::min(smallest, c);
  }
  EXPECT_DOUBLE_EQ(j["coverage"]["min"].get<double>(), smallest);
  EXPECT_NEAR(value_of(r.out, "coverage_min"), smallest, 0.0006);
  const auto& d = j["depth"];
  EXPECT_LE(d["q1_m"].get<double>(), d["median_m"].get<double>());
  EXPECT_LE(d["median_m"].get<double>(), d["q3_m"].get<double>());
  EXPECT_EQ(d["histogram"].size(), 10u);
  for (int az : {0, 90, 180, 270}) {
    char name[32];
    std::snprintf(name, sizeof name, "leaves_az%03d.png", az);
    forest::FrameImage mask = forest::read_image(dir_ / "masks" / name);
    EXPECT_EQ(mask.width, 128u) << name;
  }
}

TEST_F(CliMeasure, ModelGivesTheCoverageAndDepthOfItsPreset) {
  ASSERT_EQ(run_captured(forest_command("generate --species '" + kPreset + "' --out " + path("t.glb")), dir_).code, 0);
  ASSERT_EQ(run("--species '" + kPreset + "' --resolution 96 --json " + path("a.json")).code, 0);
  Result r = run("--model " + path("t.glb") + " --resolution 96 --json " + path("b.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("habit n/a"), std::string::npos) << r.out;
  nlohmann::json a = nlohmann::json::parse(slurp(dir_ / "a.json")), b = nlohmann::json::parse(slurp(dir_ / "b.json"));
  EXPECT_TRUE(b["habit"].is_null());
  EXPECT_FALSE(a["habit"].is_null());
  EXPECT_EQ(a["coverage"], b["coverage"]);
  EXPECT_EQ(a["depth"], b["depth"]);
}

TEST_F(CliMeasure, BadSpeciesFileExitsTwoWithOneLine) {
  std::ofstream(dir_ / "bad.toml") << "method = \"lsystem\"\niterations = nan\n";
  expect_one_line_error(run("--species " + path("bad.toml") + " --json " + path("m.json")), "bad.toml:2:");
  std::ofstream(dir_ / "unknown.toml") << "method = \"lsystem\"\nname = \"x\"\nbogus_key = 1\n";
  expect_one_line_error(run("--species " + path("unknown.toml") + " --json " + path("m.json")), "bogus_key");
}

TEST_F(CliMeasure, UsageErrorsExitTwoWithOneLine) {
  expect_one_line_error(run("--json " + path("m.json")), "--species");
  expect_one_line_error(run("--species '" + kPreset + "' --model '" + kPreset + "'"), "excludes");
  expect_one_line_error(run("--species " + path("missing.toml")), "missing.toml");
  expect_one_line_error(run("--species '" + kPreset + "' --json " + path("no/such/m.json")), "--json");
  expect_one_line_error(run("--species '" + kPreset + "' --masks " + path("no-folder")), "--masks");
  expect_one_line_error(run("--species '" + kPreset + "' --resolution 8"), "--resolution");
  std::ofstream(dir_ / "t.glb") << "not a glb";
  expect_one_line_error(run("--model " + path("t.glb") + " --seed 4"), "--seed");
  expect_one_line_error(run("--model " + path("t.glb")), "t.glb");
}
