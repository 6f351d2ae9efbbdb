// Stroke drawings (JSON / SVG): parsing, round trips and every input error.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "generators/core/input_error.h"
#include "generators/methods/common/strokes_io.h"

using namespace forest;

namespace {

std::string json_with(const std::string& strokes) {
  return "{\"format\": \"forest-drawing\", \"version\": 1, \"strokes\": [\n" + strokes + "\n]}";
}

// Expects parsing to fail with a message that contains every one of `parts`.
void expect_json_error(const std::string& text, std::initializer_list<std::string> parts) {
  try {
    parse_drawing_json(text, "d.json");
    ADD_FAILURE() << "no error for " << text;
  } catch (const InputError& e) {
    std::string m = e.what();
    for (const std::string& p : parts) EXPECT_NE(m.find(p), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos);
  }
}

}  // namespace

TEST(Strokes, JsonRoundTripKeepsEverything) {
  Drawing d;
  d.file = "x";
  Stroke a;
  a.id = "trunk";
  a.points = {{0, 0}, {0.1, 2.5}, {-0.2, 5}};
  a.depth = {0, 0.25, -1.5};
  Stroke b;
  b.id = "b";
  b.parent = "trunk";
  b.level = 1;
  b.role = "branch";
  b.points = {{0.1, 2.5}, {1.5, 3.25}};
  b.depth = {0.25, 0.75};
  d.strokes = {a, b};
  Drawing r = parse_drawing_json(drawing_to_json(d), "r.json");
  ASSERT_EQ(r.strokes.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(r.strokes[i].id, d.strokes[i].id);
    EXPECT_EQ(r.strokes[i].parent, d.strokes[i].parent);
    EXPECT_EQ(r.strokes[i].level, d.strokes[i].level);
    EXPECT_EQ(r.strokes[i].points, d.strokes[i].points);
    EXPECT_EQ(r.strokes[i].depth, d.strokes[i].depth);
  }
  EXPECT_EQ(r.strokes[1].line, 3);  // one stroke per line after the header
  EXPECT_EQ(stroke_parents(r), std::vector<int>({-1, 0}));
}

TEST(Strokes, SvgPolylinesAndPathsFlipY) {
  const char* svg = R"(<svg xmlns="http://www.w3.org/2000/svg">
  <polyline id="t" points="0,0 0,-8"/>
  <path id="c" class="silhouette" d="M 1 -2 L 3 -2 l 0 -2 Z"/>
  <path class="branch" data-parent="t" data-level="2" d="m 0 -4 l 1,-1 2,-1"/>
</svg>)";
  Drawing d = parse_drawing_svg(svg, "s.svg");
  ASSERT_EQ(d.strokes.size(), 3u);
  EXPECT_EQ(d.strokes[0].role, "branch");
  EXPECT_EQ(d.strokes[0].points, std::vector<glm::dvec2>({{0, 0}, {0, 8}}));
  EXPECT_EQ(d.strokes[1].role, "silhouette");
  EXPECT_EQ(d.strokes[1].points, std::vector<glm::dvec2>({{1, 2}, {3, 2}, {3, 4}, {1, 2}}));
  EXPECT_EQ(d.strokes[2].parent, "t");
  EXPECT_EQ(d.strokes[2].level, 2);
  // Relative line-tos after a relative move-to accumulate.
  EXPECT_EQ(d.strokes[2].points, std::vector<glm::dvec2>({{0, 4}, {1, 5}, {3, 6}}));
  EXPECT_EQ(d.strokes[2].line, 4);
  // Our SVG writer reads back to the same drawing (up to the 4 decimals it writes).
  Drawing back = parse_drawing_svg(drawing_to_svg(d), "b.svg");
  ASSERT_EQ(back.strokes.size(), 3u);
  EXPECT_EQ(back.strokes[2].points, d.strokes[2].points);
  EXPECT_EQ(back.strokes[2].parent, "t");
}

TEST(Strokes, SvgHorizontalVerticalPolygonAndLine) {
  const char* svg = R"(<svg xmlns="http://www.w3.org/2000/svg">
  <!-- a comment with <polyline points="9,9 9,9"/> inside is not a stroke -->
  <g id="layer"><path id="p" d="M0,0 H 2 V -3 h -1 v 1"/></g>
  <polygon id="q" class="silhouette" points="0,0 2,0 2,-2"/>
  <line id="l" x1="1" y1="-1" x2="4" y2="-5"/>
</svg>)";
  Drawing d = parse_drawing_svg(svg, "s.svg");
  ASSERT_EQ(d.strokes.size(), 3u);
  EXPECT_EQ(d.strokes[0].points, std::vector<glm::dvec2>({{0, 0}, {2, 0}, {2, 3}, {1, 3}, {1, 2}}));
  EXPECT_EQ(d.strokes[0].line, 3);
  EXPECT_EQ(d.strokes[1].points, std::vector<glm::dvec2>({{0, 0}, {2, 0}, {2, 2}, {0, 0}}));  // closed
  EXPECT_EQ(d.strokes[1].role, "silhouette");
  EXPECT_EQ(d.strokes[2].points, std::vector<glm::dvec2>({{1, 1}, {4, 5}}));
}

TEST(Strokes, ErrorsNameFileLineAndKey) {
  const std::string t = "{\"id\": \"t\", \"points\": [[0, 0], [0, 5]]}";
  expect_json_error("{\"strokes\": [", {"d.json:1", "JSON syntax"});
  expect_json_error(json_with(""), {"d.json", "no strokes"});
  expect_json_error(json_with("{\"id\": \"t\", \"points\": [[0, 0]]}"), {"d.json:2", "strokes[0] (t).points", "2 points"});
  expect_json_error(json_with(t + ",\n{\"id\": \"b\", \"parent\": \"b\", \"points\": [[0, 1], [1, 2]]}"),
                    {"d.json:3", "strokes[1] (b).parent", "own parent"});
  expect_json_error(json_with(t + ",\n{\"id\": \"b\", \"parent\": \"zz\", \"points\": [[0, 1], [1, 2]]}"),
                    {"d.json:3", "unknown stroke id 'zz'"});
  expect_json_error(json_with("{\"id\": \"a\", \"parent\": \"b\", \"points\": [[0, 0], [0, 5]]},\n"
                              "{\"id\": \"b\", \"parent\": \"a\", \"points\": [[0, 1], [1, 2]]}"),
                    {"d.json:2", "cycle"});
  expect_json_error(json_with(t + ",\n" + t), {"d.json:2", "duplicate id 't'"});
  expect_json_error(json_with("{\"id\": \"t\", \"points\": [[0, 0], [0, 1e9]]}"), {"d.json:2", "1e4"});
  expect_json_error(json_with("{\"id\": \"t\", \"points\": [[0, 0], [0, \"5\"]]}"), {"points", "expected a number"});
  expect_json_error(json_with("{\"id\": \"t\", \"points\": [[0, 0], [0, 5]], \"depth\": [1]}"), {"depth", "one value per point"});
  expect_json_error(json_with("{\"id\": \"t\", \"pts\": [[0, 0], [0, 5]]}"), {"pts", "unknown key"});
  expect_json_error("{\"format\": \"other\", \"strokes\": []}", {"format"});

  auto svg_error = [](const std::string& body, const std::string& part) {
    try {
      parse_drawing_svg("<svg>\n" + body + "\n</svg>", "s.svg");
      ADD_FAILURE() << body;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("s.svg:2"), std::string::npos) << e.what();
    }
  };
  svg_error("<path d=\"M 0 0 C 1 1 2 2 3 3\"/>", "unsupported path command 'C'");
  svg_error("<polyline points=\"0,0 1\"/>", "odd number");
  svg_error("<polyline points=\"0,0 nan,1\"/>", "finite");
  svg_error("<polyline points=\"0,0 1,x\"/>", "malformed");
  svg_error("<g transform=\"scale(2)\"><polyline points=\"0,0 1,1\"/></g>", "transforms are not supported");
  svg_error("<polyline transform=\"translate(1 0)\" points=\"0,0 1,1\"/>", "transform");
  svg_error("<ellipse cx=\"0\" cy=\"0\" rx=\"1\" ry=\"2\"/>", "unsupported element");
  svg_error("<path d=\"M 0 0 A 1 1 0 0 1 2 2\"/>", "unsupported path command 'A'");
  svg_error("<path d=\"L 0 0 1 1\"/>", "starts with M");
  svg_error("<path d=\"M 0 0 H\"/>", "");
  svg_error("<line x1=\"0\" y1=\"0\" x2=\"1\"/>", "y2");
  svg_error("<!-- never closed", "unterminated");
  EXPECT_THROW(parse_drawing_svg("<html></html>", "s.svg"), InputError);

  auto dir = std::filesystem::temp_directory_path() / "forest_test_strokes";
  std::filesystem::create_directories(dir);
  EXPECT_THROW(read_drawing(dir / "missing.json"), InputError);
  { std::ofstream(dir / "empty.json") << "  \n"; }
  try {
    read_drawing(dir / "empty.json");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("empty"), std::string::npos);
  }
  { std::ofstream(dir / "d.txt") << "x"; }
  EXPECT_THROW(read_drawing(dir / "d.txt"), InputError);
  std::filesystem::remove_all(dir);
}
