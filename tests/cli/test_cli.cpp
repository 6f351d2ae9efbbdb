// Runs build/forest as a user would: exit codes, one-line error messages naming file, line
// and key, no partial output files, and the happy paths of info/generate/render.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {

const std::string kSource = FOREST_SOURCE_DIR;
const std::string kExe = FOREST_EXE;

struct Result {
  int code = -1;
  std::string out, err;
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("forest_cli_" + std::to_string(getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  Result run(const std::string& args) {
    std::string cmd = "'" + kExe + "' " + args + " >'" + (dir_ / "stdout").string() + "' 2>'" +
                      (dir_ / "stderr").string() + "' </dev/null";
    int status = std::system(cmd.c_str());
    Result r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(dir_ / "stdout");
    r.err = slurp(dir_ / "stderr");
    return r;
  }
  fs::path write(const std::string& name, const std::string& text) {
    fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p;
  }
  // Only the test's own files may be in the folder (no stray output, no temp files).
  std::vector<std::string> listing() {
    std::vector<std::string> names;
    for (auto& e : fs::directory_iterator(dir_))
      if (e.path().filename() != "stdout" && e.path().filename() != "stderr") names.push_back(e.path().filename());
    std::sort(names.begin(), names.end());
    return names;
  }
  fs::path dir_;
};

size_t lines(const std::string& s) { return size_t(std::count(s.begin(), s.end(), '\n')); }

std::string scene_with(const std::string& body) {
  return "[render]\nwidth = 64\nheight = 48\n"
         "[camera]\nposition = [0, 6, -24]\ntarget = [0, 5, 0]\n"
         "[terrain]\nsize = 100\nresolution = 8\n"
         "[[species]]\npreset = \"" + kSource + "/scenes/species/broadleaf.toml\"\n" + body;
}

struct BadScene {
  const char* name;
  std::string text;
  int line;            // expected line in the message (0: none)
  const char* key;     // expected key in the message
};

}  // namespace

TEST_F(CliTest, BadSceneFilesFailWithOneLineNamingFileLineKey) {
  const BadScene cases[] = {
      {"malformed", scene_with("[placement\ncount = 3\n"), 12, ""},
      {"unknown_key", scene_with("[placement]\ncount = 3\ncolour = 1\n"), 14, "placement.colour"},
      {"wrong_type", scene_with("[placement]\ncount = \"many\"\n"), 13, "placement.count"},
      {"negative_count", scene_with("[placement]\ncount = -5\n"), 13, "placement.count"},
      {"nan", scene_with("[placement]\ncount = 3\nmin_spacing = nan\n"), 14, "placement.min_spacing"},
      {"inf", "[camera]\nfov = inf\n", 2, "camera.fov"},
      {"absurd", "[render]\nwidth = 100000\n", 2, "render.width"},
      {"absurd_tree_count", scene_with("[placement]\ncount = 100000000\n"), 13, "placement.count"},
      {"bad_vec", "[camera]\nposition = [1, 2]\n", 2, "camera.position"},
      {"missing_preset", "[[species]]\npreset = \"nope.toml\"\n", 2, "species[0].preset"},
      {"bad_tree_index", scene_with("[[tree]]\nspecies = 4\nx = 0\nz = 0\n"), 13, "tree[0].species"},
      {"unknown_table", "[rendr]\nwidth = 3\n", 1, "rendr"},
  };
  for (const BadScene& c : cases) {
    SCOPED_TRACE(c.name);
    fs::path scene = write(std::string(c.name) + ".toml", c.text);
    Result r = run("render '" + scene.string() + "' --out '" + (dir_ / "frame.png").string() + "'");
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find(scene.string()), std::string::npos) << r.err;
    if (c.line > 0) EXPECT_NE(r.err.find(":" + std::to_string(c.line) + ":"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.key), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "frame.png"));
    std::vector<std::string> files = listing();
    EXPECT_EQ(files, std::vector<std::string>{std::string(c.name) + ".toml"});
    fs::remove(scene);
  }
}

TEST_F(CliTest, AbsurdLeafCountInModelExitsTwo) {
  // A .glb that declares 10^7 leaves (and stores 4): refused before anything is allocated.
  const std::string glb = kSource + "/tests/fuzz/corpus/glb/absurd_leaf_count.glb";
  fs::path scene = write("s.toml", "[[species]]\nmodel = \"" + glb + "\"\n[[tree]]\nx = 0\nz = 0\n");
  Result r = run("render '" + scene.string() + "' --out '" + (dir_ / "frame.png").string() + "'");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find(glb + ": "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("10000000 leaves, more than the limit"), std::string::npos) << r.err;
  EXPECT_EQ(listing(), std::vector<std::string>{"s.toml"});
}

TEST_F(CliTest, MissingSceneFile) {
  Result r = run("render '" + (dir_ / "absent.toml").string() + "' --out '" + (dir_ / "f.png").string() + "'");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(lines(r.err), 1u);
  EXPECT_NE(r.err.find("absent.toml"), std::string::npos);
  EXPECT_TRUE(listing().empty());
}

TEST_F(CliTest, MissingOutputFolder) {
  fs::path scene = write("ok.toml", scene_with(""));
  Result r = run("render '" + scene.string() + "' --out '" + (dir_ / "no/such/f.png").string() + "'");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(lines(r.err), 1u);
  EXPECT_NE(r.err.find("--out"), std::string::npos) << r.err;
}

TEST_F(CliTest, UsageErrorsExitTwo) {
  EXPECT_EQ(run("").code, 2);
  EXPECT_EQ(run("frobnicate").code, 2);
  EXPECT_EQ(run("render").code, 2);
  EXPECT_EQ(run("generate --method lsystem").code, 2);  // --out missing
  Result r = run("generate --method nosuch --out '" + (dir_ / "t.glb").string() + "'");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(lines(r.err), 1u);
  EXPECT_TRUE(listing().empty());
}

TEST_F(CliTest, BadSpeciesFileFailsWithoutOutput) {
  fs::path species = write("bad.toml", "method = \"lsystem\"\niterations = nan\n");
  Result r = run("generate --species '" + species.string() + "' --out '" + (dir_ / "t.glb").string() + "'");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("bad.toml:2:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("iterations"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "t.glb"));
}

TEST_F(CliTest, InfoListsDevicesAndFeatures) {
  Result r = run("info");
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* f : {"drawIndirectCount", "shaderDrawParameters", "samplerFilterMinmax", "dynamicRendering",
                        "synchronization2", "timestamps"})
    EXPECT_NE(r.out.find(f), std::string::npos) << f;
  EXPECT_NE(r.out.find("chosen:"), std::string::npos);
  EXPECT_EQ(r.out.find("MISSING"), std::string::npos);
  Result bad = run("info --device no-such-gpu");
  EXPECT_EQ(bad.code, 2);
  EXPECT_EQ(lines(bad.err), 1u);
}

TEST_F(CliTest, GenerateIsDeterministic) {
  std::string species = kSource + "/scenes/species/fig2_1.toml";
  ASSERT_EQ(run("generate --species '" + species + "' --seed 5 --out '" + (dir_ / "a.glb").string() + "'").code, 0);
  ASSERT_EQ(run("generate --method lsystem --species '" + species + "' --seed 5 --out '" + (dir_ / "b.glb").string() + "'").code, 0);
  ASSERT_EQ(run("generate --species '" + species + "' --seed 6 --out '" + (dir_ / "c.glb").string() + "'").code, 0);
  std::string a = slurp(dir_ / "a.glb"), b = slurp(dir_ / "b.glb"), c = slurp(dir_ / "c.glb");
  EXPECT_GT(a.size(), 1000u);
  EXPECT_EQ(a.substr(0, 4), "glTF");
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

TEST_F(CliTest, RenderWritesPngAndNothingElse) {
  fs::path scene = write("ok.toml", scene_with("[[tree]]\nspecies = 0\nx = 0\nz = 0\n"));
  Result r = run("render '" + scene.string() + "' --out '" + (dir_ / "frame.png").string() + "' --validate --stats");
  ASSERT_EQ(r.code, 0) << r.err;
  std::string png = slurp(dir_ / "frame.png");
  ASSERT_GT(png.size(), 100u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  EXPECT_EQ(listing(), (std::vector<std::string>{"frame.png", "ok.toml"}));
  EXPECT_NE(r.out.find("1 trees, 1 visible"), std::string::npos) << r.out;
}

TEST_F(CliTest, BakeReportAndRenderOpt) {
  std::string species = kSource + "/scenes/species/broadleaf.toml";
  fs::path raw = dir_ / "raw.glb", baked = dir_ / "baked.glb", report = dir_ / "report";
  ASSERT_EQ(run("generate --species '" + species + "' --out '" + raw.string() + "'").code, 0);
  Result b = run("bake '" + raw.string() + "' --out '" + baked.string() + "' --views 2 --resolution 64 --priority combined");
  ASSERT_EQ(b.code, 0) << b.err;
  EXPECT_NE(b.out.find("combined order"), std::string::npos) << b.out;
  std::string glb = slurp(baked);
  EXPECT_NE(glb.find("\"pr_tables\""), std::string::npos);
  EXPECT_NE(glb.find("\"hull\""), std::string::npos);
  Result r = run("report '" + baked.string() + "' --out '" + report.string() + "'");
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* f : {"pr_diagram.png", "scale_vs_lambda.png", "lambda_vs_distance.png", "scale_table.csv",
                        "lambda_table.csv", "pr_samples.csv"})
    EXPECT_GT(fs::file_size(report / f), 100u) << f;
  // An unbaked model has no tables to report.
  Result u = run("report '" + raw.string() + "' --out '" + report.string() + "'");
  EXPECT_EQ(u.code, 2);
  EXPECT_NE(u.err.find("not baked"), std::string::npos);
  // The baked model renders in mode opt.
  fs::path scene = write("opt.toml", "[render]\nwidth = 64\nheight = 48\nmode = \"opt\"\n"
                                      "[camera]\nposition = [0, 6, -24]\ntarget = [0, 5, 0]\n"
                                      "[terrain]\nsize = 100\nresolution = 8\n"
                                      "[[species]]\nmodel = \"" + baked.string() + "\"\n"
                                      "[[tree]]\nspecies = 0\nx = 0\nz = 0\n");
  Result o = run("render '" + scene.string() + "' --out '" + (dir_ / "opt.png").string() + "' --stats");
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.out.find("1 visible"), std::string::npos) << o.out;
}
