// Runs build/forest as a user would: exit codes, one-line error messages naming file, line
// and key, no partial output files, and the happy paths of info/generate/render.
#include <gtest/gtest.h>
#include <expat.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "engine/present/image_io.h"
#include "tests/cli/cli_run.h"

namespace fs = std::filesystem;
using namespace forest::test;

namespace {

class CliTest : public CliDirTest {
 protected:
  Result run(const std::string& args) { return run_captured(forest_command(args), dir_); }
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
};

std::string scene_with(const std::string& body) {
  return "[render]\nwidth = 64\nheight = 48\n"
         "[camera]\nposition = [0, 6, -24]\ntarget = [0, 5, 0]\n"
         "[terrain]\nsize = 100\nresolution = 8\n"
         "[[species]]\npreset = \"" + kSourceDir + "/scenes/species/broadleaf.toml\"\n" + body +
         "\n[bake]\nviews = 1\nresolution = 32\nimpostor = false\n";  // presets are baked on first use: keep it cheap
}

// Parses XML with expat: false when it is not well-formed; counts <polyline> elements.
bool parse_xml(const std::string& text, size_t& polylines, std::string& root) {
  struct State {
    size_t polylines = 0;
    std::string root;
  } state;
  XML_Parser parser = XML_ParserCreate(nullptr);
  XML_SetUserData(parser, &state);
  XML_SetStartElementHandler(parser, [](void* data, const XML_Char* name, const XML_Char**) {
    State& st = *static_cast<State*>(data);
    if (st.root.empty()) st.root = name;
    if (std::string(name) == "polyline") ++st.polylines;
  });
  bool ok = XML_Parse(parser, text.data(), int(text.size()), 1) == XML_STATUS_OK;
  XML_ParserFree(parser);
  polylines = state.polylines;
  root = state.root;
  return ok;
}

// The integer after `"key":` in a glb's JSON chunk (-1 if absent).
long json_int(const std::string& glb, const std::string& key) {
  size_t at = glb.find("\"" + key + "\":");
  return at == std::string::npos ? -1 : std::atol(glb.c_str() + at + key.size() + 3);
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
    if (c.line > 0) {
      EXPECT_NE(r.err.find(":" + std::to_string(c.line) + ":"), std::string::npos) << r.err;
    }
    EXPECT_NE(r.err.find(c.key), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "frame.png"));
    std::vector<std::string> files = listing();
    EXPECT_EQ(files, std::vector<std::string>{std::string(c.name) + ".toml"});
    fs::remove(scene);
  }
}

TEST_F(CliTest, AbsurdLeafCountInModelExitsTwo) {
  // A .glb that declares 10^7 leaves (and stores 4): refused before anything is allocated.
  const std::string glb = kSourceDir + "/tests/fuzz/corpus/glb/absurd_leaf_count.glb";
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

// The depth pyramid overlay shows what occlusion tests against: without occlusion there is
// nothing to show, which is an input error before anything is generated or written.
TEST_F(CliTest, PyramidOverlayNeedsOcclusion) {
  fs::path scene = write("ok.toml", scene_with(""));
  fs::path out = dir_ / "f.png";
  Result r = run("render '" + scene.string() + "' --out '" + out.string() + "' --overlay pyramid");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("--overlay"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(run("render '" + scene.string() + "' --out '" + out.string() + "' --overlay depth").code, 2);
  Result ok = run("render '" + scene.string() + "' --out '" + out.string() + "' --overlay pyramid --occlusion on");
  EXPECT_EQ(ok.code, 0) << ok.err;
  EXPECT_TRUE(fs::exists(out));
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
  EXPECT_EQ(run("render s.toml --out f.png --occlusion maybe").code, 2);
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
  std::string species = kSourceDir + "/scenes/species/fig2_1.toml";
  ASSERT_EQ(run("generate --species '" + species + "' --seed 5 --out '" + (dir_ / "a.glb").string() + "'").code, 0);
  ASSERT_EQ(run("generate --method lsystem --species '" + species + "' --seed 5 --out '" + (dir_ / "b.glb").string() + "'").code, 0);
  ASSERT_EQ(run("generate --species '" + species + "' --seed 6 --out '" + (dir_ / "c.glb").string() + "'").code, 0);
  std::string a = slurp(dir_ / "a.glb"), b = slurp(dir_ / "b.glb"), c = slurp(dir_ / "c.glb");
  EXPECT_GT(a.size(), 1000u);
  EXPECT_EQ(a.substr(0, 4), "glTF");
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

TEST_F(CliTest, PreviewBarkLodsShowsEveryLevelInARow) {
  std::string species = kSourceDir + "/scenes/species/broadleaf.toml";
  ASSERT_EQ(run("generate --species '" + species + "' --out '" + (dir_ / "t.glb").string() + "'").code, 0);
  Result r = run("preview '" + (dir_ / "t.glb").string() + "' --bark-lods --size 64 --out '" +
                 (dir_ / "lods.png").string() + "'");
  ASSERT_EQ(r.code, 0) << r.err;
  // One view per level, LOD0 first, each line naming its triangles: fewer every level.
  size_t levels = 0, previous = SIZE_MAX;
  for (size_t at = r.out.find("LOD"); at != std::string::npos; at = r.out.find("LOD", at + 1)) {
    size_t triangles = std::stoul(r.out.substr(r.out.find(": ", at) + 2));
    EXPECT_LT(triangles, previous) << r.out;
    previous = triangles;
    ++levels;
  }
  EXPECT_GE(levels, 6u) << r.out;
  forest::FrameImage sheet = forest::read_image(dir_ / "lods.png");
  // One row of `levels` views (the sheet adds thin borders).
  EXPECT_GE(sheet.width, 64u * levels);
  EXPECT_LT(sheet.width, 64u * (levels + 1));
  EXPECT_GE(sheet.height, 64u);
  EXPECT_LT(sheet.height, 128u);
}

TEST_F(CliTest, LearnThenGeneratePlantons) {
  fs::path model = dir_ / "m.json";
  Result l = run("learn --ground-truth --trees 2 --seed 3 --out '" + model.string() + "'");
  ASSERT_EQ(l.code, 0) << l.err;
  EXPECT_NE(l.out.find("plantons after k-means"), std::string::npos) << l.out;
  std::string text = slurp(model);
  EXPECT_NE(text.find("\"forest-plantons\""), std::string::npos);
  // Same seed, same bytes.
  ASSERT_EQ(run("learn --ground-truth --trees 2 --seed 3 --out '" + (dir_ / "m2.json").string() + "'").code, 0);
  EXPECT_EQ(slurp(dir_ / "m2.json"), text);
  // A preset naming the model (relative to the preset) generates a tree.
  fs::path species = write("p.toml", "method = \"plantons\"\nseed = 2\nmodel = \"m.json\"\nmax_organs = 500\n");
  Result g = run("generate --species '" + species.string() + "' --out '" + (dir_ / "t.glb").string() + "'");
  ASSERT_EQ(g.code, 0) << g.err;
  EXPECT_EQ(slurp(dir_ / "t.glb").substr(0, 4), "glTF");
  // Samples from another method's preset.
  fs::path lsystem = write("l.toml", "method = \"lsystem\"\nseed = 3\niterations = 3\naxiom = \"X\"\nstep = 0.5\n"
                                     "leaf_size = 0.1\n[[production]]\npredecessor = \"X\"\nsuccessor = \"F[+X]F[-X]/X\"\n");
  Result s = run("learn --species '" + lsystem.string() + "' --trees 2 --out '" + (dir_ / "f.json").string() + "'");
  EXPECT_EQ(s.code, 0) << s.err;
  // No source, two sources: usage errors.
  EXPECT_EQ(run("learn --out '" + (dir_ / "x.json").string() + "'").code, 2);
  EXPECT_EQ(run("learn --ground-truth --samples '" + model.string() + "' --out '" + (dir_ / "x.json").string() + "'").code, 2);
  EXPECT_FALSE(fs::exists(dir_ / "x.json"));
}

TEST_F(CliTest, BadPlantonModelFailsWithOneLine) {
  fs::path model = write("m.json", "{\"format\": \"forest-plantons\",\n \"version\": 1,\n \"plantons\": [}\n");
  fs::path species = write("p.toml", "method = \"plantons\"\nmodel = \"m.json\"\n");
  Result r = run("generate --species '" + species.string() + "' --out '" + (dir_ / "t.glb").string() + "'");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("m.json:3:"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "t.glb"));
  fs::path missing = write("q.toml", "method = \"plantons\"\nmodel = \"absent.json\"\n");
  Result m = run("generate --species '" + missing.string() + "' --out '" + (dir_ / "t.glb").string() + "'");
  EXPECT_EQ(m.code, 2);
  EXPECT_NE(m.err.find("q.toml:2:"), std::string::npos) << m.err;
  // A sample file that is not one.
  Result s = run("learn --samples '" + model.string() + "' --out '" + (dir_ / "o.json").string() + "'");
  EXPECT_EQ(s.code, 2);
  EXPECT_EQ(lines(s.err), 1u) << s.err;
  EXPECT_FALSE(fs::exists(dir_ / "t.glb"));
  EXPECT_FALSE(fs::exists(dir_ / "o.json"));
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
  // With occlusion feedback: the same picture (one tree in plain view), and its statistics.
  Result o = run("render '" + scene.string() + "' --out '" + (dir_ / "occl.png").string() +
                 "' --validate --stats --occlusion on");
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_EQ(slurp(dir_ / "occl.png"), png);
  EXPECT_NE(o.out.find("occlusion: 0 trees culled"), std::string::npos) << o.out;
}

TEST_F(CliTest, BakeReportAndRenderOpt) {
  std::string species = kSourceDir + "/scenes/species/broadleaf.toml";
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

TEST_F(CliTest, CompareMaskRendersOfFullAndCook) {
  std::string tree = "[[tree]]\nspecies = 0\nx = 0\nz = 0\n";
  auto mask_scene = [&](const std::string& name, const std::string& mode) {
    std::string text = scene_with(tree);
    text.insert(text.find("[camera]"), "view = \"mask\"\nmode = \"" + mode + "\"\nprune_distance = 40\n");
    // Large enough that the crown's gaps show: at 64 x 48 a dense crown is one solid blot.
    text.replace(text.find("width = 64\nheight = 48"), 22, "width = 192\nheight = 144");
    return write(name, text);
  };
  fs::path full = dir_ / "full.png", cook = dir_ / "cook.png", diff = dir_ / "diff.png";
  ASSERT_EQ(run("render '" + mask_scene("full.toml", "full").string() + "' --out '" + full.string() + "'").code, 0);
  ASSERT_EQ(run("render '" + mask_scene("cook.toml", "cook").string() + "' --out '" + cook.string() + "'").code, 0);

  Result same = run("compare '" + full.string() + "' '" + full.string() + "' --min-quality 1");
  ASSERT_EQ(same.code, 0) << same.err;
  EXPECT_NE(same.out.find("Q 1.0000"), std::string::npos) << same.out;

  // Cook at d = 0.6 keeps 16 % of the leaves scaled by 6.25: a visible difference.
  Result pruned = run("compare '" + full.string() + "' '" + cook.string() + "' --diff '" + diff.string() + "'");
  ASSERT_EQ(pruned.code, 0) << pruned.err;
  double p = 0, r = 0, q = 0;
  ASSERT_EQ(std::sscanf(pruned.out.c_str(), "P %lf R %lf Q %lf", &p, &r, &q), 3) << pruned.out;
  EXPECT_LT(q, 0.99);
  EXPECT_GT(q, 0.0);
  EXPECT_GT(fs::file_size(diff), 100u);
  Result below = run("compare '" + full.string() + "' '" + cook.string() + "' --min-quality 0.999");
  EXPECT_EQ(below.code, 3);
  EXPECT_EQ(lines(below.err), 1u) << below.err;

  // Different sizes: one line naming both files, exit 2.
  fs::path small = dir_ / "small.png";
  ASSERT_EQ(run("render '" + mask_scene("small.toml", "full").string() + "' --width 32 --out '" + small.string() + "'").code, 0);
  Result bad = run("compare '" + full.string() + "' '" + small.string() + "'");
  EXPECT_EQ(bad.code, 2);
  EXPECT_EQ(lines(bad.err), 1u) << bad.err;
  EXPECT_NE(bad.err.find("small.png"), std::string::npos) << bad.err;
  // A corrupt PNG is an input error too.
  fs::path corrupt = write("corrupt.png", "\x89PNG not really");
  EXPECT_EQ(run("compare '" + full.string() + "' '" + corrupt.string() + "'").code, 2);
}

// A small 2D magnetic species: few curves, quick.
const char* kMagnetic2d = R"(method = "magnetic"
seed = 4
mode = "2d"
size = [300.0, 400.0, 1.0]
cell = 4.0
dt = 0.5
trunk_q0 = 0.25
child_spacing = 60.0
max_curves = 12
max_depth = 3
scale = 0.03
leaf_size = 0.1
)";

TEST_F(CliTest, GenerateSvgWritesOnePolylinePerCurve) {
  fs::path species = write("klimt.toml", kMagnetic2d);
  fs::path glb = dir_ / "m.glb", svg = dir_ / "m.svg";
  Result r = run("generate --species '" + species.string() + "' --out '" + glb.string() + "' --svg '" + svg.string() + "'");
  ASSERT_EQ(r.code, 0) << r.err;
  std::string text = slurp(svg);
  size_t polylines = 0;
  std::string root;
  ASSERT_TRUE(parse_xml(text, polylines, root)) << text.substr(0, 200);
  EXPECT_EQ(root, "svg");
  long curves = json_int(slurp(glb), "curves");
  ASSERT_GT(curves, 1);
  EXPECT_EQ(long(polylines), curves);
  EXPECT_NE(r.out.find("m.svg: " + std::to_string(curves) + " curves"), std::string::npos) << r.out;
  // --svg alone, another seed: a different drawing; the same seed again: the same bytes.
  fs::path svg2 = dir_ / "s2.svg", svg3 = dir_ / "s3.svg";
  ASSERT_EQ(run("generate --species '" + species.string() + "' --svg '" + svg2.string() + "'").code, 0);
  ASSERT_EQ(run("generate --species '" + species.string() + "' --seed 9 --svg '" + svg3.string() + "'").code, 0);
  EXPECT_EQ(slurp(svg2), text);
  EXPECT_NE(slurp(svg3), text);
  EXPECT_EQ(listing(), (std::vector<std::string>{"klimt.toml", "m.glb", "m.svg", "s2.svg", "s3.svg"}));
}

TEST_F(CliTest, GenerateSvgNeedsPlanarCurves) {
  fs::path svg = dir_ / "x.svg", glb = dir_ / "x.glb";
  // A method without curves: one line naming the key, exit 2, no file at all.
  Result r = run("generate --species '" + kSourceDir + "/scenes/species/broadleaf.toml' --out '" + glb.string() +
                 "' --svg '" + svg.string() + "'");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("broadleaf.toml:1: method"), std::string::npos) << r.err;
  // The 3D variant has no planar curves.
  std::string text = kMagnetic2d;
  text.replace(text.find("mode = \"2d\""), 11, "mode = \"3d\"");
  fs::path species = write("m3.toml", text);
  r = run("generate --species '" + species.string() + "' --svg '" + svg.string() + "'");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("m3.toml:3: mode"), std::string::npos) << r.err;
  // Neither --out nor --svg.
  EXPECT_EQ(run("generate --method magnetic").code, 2);
  EXPECT_EQ(listing(), (std::vector<std::string>{"m3.toml"}));
}

TEST_F(CliTest, GalleryBadInputsExitTwoWithoutOutput) {
  fs::path out = dir_ / "sheet.png";
  Result r = run("gallery --species-dir '" + (dir_ / "nope").string() + "' --out '" + out.string() + "'");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("--species-dir"), std::string::npos) << r.err;
  write("bad.toml", "method = \"mgv\"\nnodes = -5\n");
  r = run("gallery --species-dir '" + dir_.string() + "' --out '" + out.string() + "'");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("bad.toml:2: nodes"), std::string::npos) << r.err;
  EXPECT_EQ(run("gallery --species-dir '" + dir_.string() + "'").code, 2);  // --out is required
  EXPECT_EQ(run("gallery --out '" + out.string() + "' --size 5").code, 2);
  EXPECT_EQ(listing(), (std::vector<std::string>{"bad.toml"}));
}

TEST_F(CliTest, RenderAlongCameraPath) {
  fs::path scene = write("path.toml", scene_with("[[tree]]\nspecies = 0\nx = 0\nz = 0\n") +
                                          "[[path]]\nname = \"orbit\"\nfps = 10\n"
                                          "[[path.key]]\ntime = 0\nposition = [0, 6, -24]\ntarget = [0, 5, 0]\n"
                                          "[[path.key]]\ntime = 2\nposition = [24, 6, 0]\ntarget = [0, 5, 0]\n");
  std::string base = "render '" + scene.string() + "' --out '";
  ASSERT_EQ(run(base + (dir_ / "a.png").string() + "' --path orbit --frame 0").code, 0);
  Result b = run(base + (dir_ / "b.png").string() + "' --path orbit --frame 10");  // t = 1 s
  ASSERT_EQ(b.code, 0) << b.err;
  ASSERT_EQ(run(base + (dir_ / "c.png").string() + "' --path orbit --time 1").code, 0);
  EXPECT_NE(slurp(dir_ / "a.png"), slurp(dir_ / "b.png"));
  EXPECT_EQ(slurp(dir_ / "b.png"), slurp(dir_ / "c.png")) << "frame 10 at 10 fps is t = 1 s";
  Result unknown = run(base + (dir_ / "e.png").string() + "' --path walk");
  EXPECT_EQ(unknown.code, 2);
  EXPECT_NE(unknown.err.find("--path: no [[path]] named 'walk'"), std::string::npos) << unknown.err;
  EXPECT_EQ(lines(unknown.err), 1u);
  Result no_path = run(base + (dir_ / "e.png").string() + "' --frame 3");
  EXPECT_EQ(no_path.code, 2);
  EXPECT_NE(no_path.err.find("--frame: needs --path"), std::string::npos) << no_path.err;
  EXPECT_EQ(run(base + (dir_ / "e.png").string() + "' --path orbit --frame 1 --time 1").code, 2);
  EXPECT_FALSE(fs::exists(dir_ / "e.png"));
}

// forest export: a .glb per level, named by --out; bad input exits 2 with one line and
// leaves nothing behind (the client checks are tests/tools/client_import_test.py).
TEST_F(CliTest, ExportWritesOneFilePerLevelAndRefusesBadInput) {
  std::string species = kSourceDir + "/scenes/species/broadleaf.toml";
  ASSERT_EQ(run("generate --species '" + species + "' --out '" + (dir_ / "t.glb").string() + "'").code, 0);
  fs::create_directories(dir_ / "out");
  Result r = run("export '" + (dir_ / "t.glb").string() + "' --out '" + (dir_ / "out/oak.glb").string() + "' --flatten");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;  // no bar in a pipe
  std::vector<std::string> files;
  for (auto& e : fs::directory_iterator(dir_ / "out")) files.push_back(e.path().filename());
  std::sort(files.begin(), files.end());
  ASSERT_GE(files.size(), 6u);
  EXPECT_EQ(files[0], "oak.glb");
  for (size_t i = 1; i < files.size(); ++i) EXPECT_EQ(files[i], "oak_LOD" + std::to_string(i) + ".glb");
  EXPECT_EQ(lines(r.out), files.size()) << r.out;  // one line per level
  EXPECT_NE(r.out.find("one mesh, COLOR_0"), std::string::npos) << r.out;
  fs::remove_all(dir_ / "out");

  const std::string model = "'" + (dir_ / "t.glb").string() + "'";
  struct Bad {
    std::string args, needle;
  };
  std::ofstream(dir_ / "corrupt.glb") << "glTF but not really";
  for (const Bad& b : {Bad{"'" + (dir_ / "missing.glb").string() + "' --out '" + (dir_ / "x.glb").string() + "'", "missing.glb"},
                       Bad{"'" + (dir_ / "corrupt.glb").string() + "' --out '" + (dir_ / "x.glb").string() + "'", "corrupt.glb"},
                       Bad{model + " --out '" + (dir_ / "x.gltf").string() + "'", "--out"},
                       Bad{model + " --out '" + (dir_ / "nosuch/x.glb").string() + "'", "--out"}}) {
    Result e = run("export " + b.args);
    EXPECT_EQ(e.code, 2) << b.args << "\n" << e.err;
    EXPECT_EQ(lines(e.err), 1u) << e.err;
    EXPECT_NE(e.err.find(b.needle), std::string::npos) << e.err;
    EXPECT_EQ(listing(), (std::vector<std::string>{"corrupt.glb", "t.glb"})) << b.args;
  }
}
