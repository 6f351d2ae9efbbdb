// `forest generate` on bad image and sketch inputs (issue 3): an empty mask, a camera whose
// size differs from its mask, a stroke file whose parent links form a cycle and a malformed
// SVG each give exit code 2, one line naming the file (and line where there is one), and no
// output file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "engine/present/image_io.h"
#include "tests/cli/cli_run.h"

namespace fs = std::filesystem;
using namespace forest::test;

namespace {

class CliImageInputs : public CliDirTest {
 protected:
  fs::path write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return dir_ / name;
  }
  // Runs `forest generate` on a species file; returns the exit code, stderr in err_.
  int generate(const std::string& species_text) {
    fs::path species = write("s.toml", species_text);
    Result r = run_captured(
        forest_command("generate --species '" + species.string() + "' --out '" + (dir_ / "t.glb").string() + "'"), dir_);
    err_ = r.err;
    return r.code;
  }
  void expect_one_line_error(const std::string& species_text, const std::string& where, const std::string& what) {
    EXPECT_EQ(generate(species_text), 2) << err_;
    EXPECT_EQ(lines(err_), 1u) << err_;
    EXPECT_NE(err_.find(where), std::string::npos) << err_;
    EXPECT_NE(err_.find(what), std::string::npos) << err_;
    EXPECT_FALSE(fs::exists(dir_ / "t.glb"));
  }
  // A copy of the committed particle-flow oak inputs (two masks + poses) in the test folder.
  std::string oak_views() {
    fs::path src = fs::path(FOREST_SOURCE_DIR) / "scenes/inputs/particle-flow/oak";
    for (const char* f : {"views.json", "view0.png", "view1.png"}) fs::copy_file(src / f, dir_ / f);
    return slurp(dir_ / "views.json");
  }
  std::string err_;
};

// Replaces the first occurrence of `from` in `s` after `after`.
std::string replace_after(std::string s, const std::string& after, const std::string& from, const std::string& to) {
  size_t at = s.find(from, s.find(after));
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

}  // namespace

TEST_F(CliImageInputs, EmptyMask) {
  std::string views = oak_views();  // 128 x 128 masks
  // An all-background image of the same size (masks are PNG or OpenEXR).
  forest::FrameImage empty;
  empty.width = empty.height = 128;
  empty.rgba.assign(128 * 128 * 4, 0);
  forest::write_image(empty, dir_ / "empty.png");
  write("views.json", replace_after(views, "\"views\"", "view1.png", "empty.png"));
  expect_one_line_error("method = \"particle-flow\"\nviews = \"views.json\"\n", "empty.png", "mask is empty");
}

TEST_F(CliImageInputs, CameraSizeDiffersFromMask) {
  std::string views = oak_views();
  size_t at = views.find("\"width\"");
  ASSERT_NE(at, std::string::npos);
  size_t colon = views.find(':', at), end = views.find_first_of(",}", colon);
  views.replace(colon + 1, end - colon - 1, " 17");
  write("views.json", views);
  expect_one_line_error("method = \"visual-hull\"\nviews = \"views.json\"\n", "views.json", "differs from mask");
}

TEST_F(CliImageInputs, StrokeFileWithACycle) {
  write("cycle.json",
        "{\"format\": \"forest-drawing\", \"version\": 1, \"strokes\": [\n"
        "{\"id\": \"a\", \"parent\": \"b\", \"points\": [[0, 0], [0, 5]]},\n"
        "{\"id\": \"b\", \"parent\": \"a\", \"points\": [[0, 1], [1, 2]]}\n]}\n");
  expect_one_line_error("method = \"sketch-mrf\"\nstrokes = \"cycle.json\"\n", "cycle.json:2", "cycle");
}

TEST_F(CliImageInputs, MalformedSvg) {
  write("bad.svg", "<svg xmlns=\"http://www.w3.org/2000/svg\">\n<polyline points=\"0,0 0,-5\"/>\n"
                   "<path d=\"M 0 0 C 1 1 2 2 3 3\"/>\n</svg>\n");
  expect_one_line_error("method = \"sketch-mrf\"\nstrokes = \"bad.svg\"\n", "bad.svg:3", "unsupported path command");
  write("bad2.svg", "<svg>\n<g transform=\"rotate(30)\">\n<polyline points=\"0,0 0,-5\"/>\n</g>\n</svg>\n");
  expect_one_line_error("method = \"silhouettes\"\ndrawing = \"bad2.svg\"\n", "bad2.svg:2", "transform");
}
