// The house rules of the source tree, checked on every test run: files small enough to read
// in one sitting, engine functions short enough to follow, and dependencies that point one
// way (docs/architecture.md): generators never include Vulkan or the engine; the run-time
// engine never includes the tools, the bench or the CPU bake; tools never include the app.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kSource = FOREST_SOURCE_DIR;
constexpr size_t kMaxFileLines = 600;
constexpr size_t kMaxEngineFunctionLines = 80;

std::vector<fs::path> sources(const std::vector<std::string>& roots) {
  std::vector<fs::path> out;
  for (const std::string& root : roots)
    for (const auto& e : fs::recursive_directory_iterator(kSource / root)) {
      std::string ext = e.path().extension().string();
      if (e.is_regular_file() && (ext == ".cpp" || ext == ".h" || ext == ".comp" || ext == ".vert" ||
                                  ext == ".frag" || ext == ".glsl"))
        out.push_back(e.path());
    }
  return out;
}

std::vector<std::string> lines_of(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string rel(const fs::path& p) { return fs::relative(p, kSource).generic_string(); }

// The code of a line without comments and string or character literals (a block comment
// spanning lines is tracked through `in_comment`).
std::string code_of(const std::string& line, bool& in_comment) {
  std::string out;
  for (size_t i = 0; i < line.size(); ++i) {
    if (in_comment) {
      if (line.compare(i, 2, "*/") == 0) in_comment = false, ++i;
      continue;
    }
    if (line.compare(i, 2, "//") == 0) break;
    if (line.compare(i, 2, "/*") == 0) {
      in_comment = true, ++i;
      continue;
    }
    if (line[i] == '"' || line[i] == '\'') {
      char quote = line[i];
      for (++i; i < line.size() && line[i] != quote; ++i)
        if (line[i] == '\\') ++i;
      continue;
    }
    out += line[i];
  }
  return out;
}

struct Function {
  size_t first_line = 0, lines = 0;
  std::string head;
};

// Function bodies at namespace scope: a '{' that opens at depth 0 (namespaces do not count)
// on a line whose code has a ')' before it, as a definition has; the body ends where the
// depth returns to 0. Class bodies, initializer lists and enums are not functions.
std::vector<Function> functions_of(const std::vector<std::string>& lines) {
  static const std::regex preprocessor(R"(^\s*#)");
  static const std::regex namespace_open(R"(^\s*(inline\s+)?namespace\b[^;]*\{)");
  static const std::regex lone_close(R"(\s*\}\s*)");
  static const std::regex not_a_body(R"((\bstruct|\bclass|\benum|\bunion|=)\s*[^()]*\{$)");
  std::vector<Function> out;
  bool in_comment = false;
  int depth = 0;
  std::string pending;  // code since the last statement or body at depth 0
  Function current;
  for (size_t n = 0; n < lines.size(); ++n) {
    std::string code = code_of(lines[n], in_comment);
    if (depth == 0 && std::regex_search(code, preprocessor)) {
      pending.clear();
      continue;  // preprocessor lines
    }
    if (depth == 0 && std::regex_search(code, namespace_open)) {
      pending.clear();
      continue;  // a namespace's braces are not a depth
    }
    if (depth == 0 && std::regex_match(code, lone_close) && current.lines == 0) continue;
    for (char c : code) {
      if (depth == 0) pending += c;
      if (c == '{') {
        if (depth == 0) {
          bool is_function = pending.find(')') != std::string::npos &&
                             !std::regex_search(pending, not_a_body);
          current = {n + 1, 0, is_function ? pending : std::string()};
        }
        ++depth;
      } else if (c == '}') {
        if (--depth == 0) {
          if (!current.head.empty()) out.push_back({current.first_line, n + 2 - current.first_line, current.head});
          current = {};
          pending.clear();
        }
        if (depth < 0) depth = 0;  // the closing brace of a namespace
      } else if (c == ';' && depth == 0) {
        pending.clear();
      }
    }
  }
  return out;
}

std::vector<std::string> includes_of(const fs::path& file) {
  std::vector<std::string> out;
  static const std::regex include(R"(^\s*#\s*include\s*[<"]([^>"]+)[>"])");
  for (const std::string& line : lines_of(file)) {
    std::smatch m;
    if (std::regex_search(line, m, include)) out.push_back(m[1]);
  }
  return out;
}

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

}  // namespace

TEST(House, NoSourceFileOver600Lines) {
  size_t checked = 0;
  for (const fs::path& f : sources({"engine", "generators", "shaders", "bench", "tests"})) {
    ++checked;
    EXPECT_LE(lines_of(f).size(), kMaxFileLines) << rel(f);
  }
  EXPECT_GT(checked, 200u) << "the source tree was not found";
}

TEST(House, NoEngineFunctionOver80Lines) {
  size_t functions = 0;
  for (const fs::path& f : sources({"engine"})) {
    if (f.extension() != ".cpp" && f.extension() != ".h") continue;
    for (const Function& fn : functions_of(lines_of(f))) {
      ++functions;
      EXPECT_LE(fn.lines, kMaxEngineFunctionLines) << rel(f) << ":" << fn.first_line << " (" << fn.lines << " lines)";
    }
  }
  EXPECT_GT(functions, 200u) << "the function scanner found too few functions";
}

TEST(House, TheFunctionScannerMeasuresBodies) {
  std::vector<std::string> code = {
      "namespace forest {",           // 1
      "struct A { int f() { return 1; } };",
      "const int table[] = {1, 2};",
      "int g(int x) {",               // 4
      "  auto l = [](int y) { return y; };",
      "  if (x) {",
      "    return l(x);  // }",
      "  }",
      "  return \"}\"[0];",
      "}",                            // 10
      "void h() {}",                  // 11
      "}  // namespace forest",
  };
  std::vector<Function> fns = functions_of(code);
  ASSERT_EQ(fns.size(), 2u);
  EXPECT_EQ(fns[0].first_line, 4u);
  EXPECT_EQ(fns[0].lines, 7u);
  EXPECT_EQ(fns[1].first_line, 11u);
  EXPECT_EQ(fns[1].lines, 1u);
}

TEST(House, DependenciesPointOneWay) {
  struct Rule {
    std::vector<std::string> roots;      // files these rules apply to
    std::vector<std::string> forbidden;  // include prefixes they must not use
  };
  const Rule rules[] = {
      {{"generators"}, {"engine/", "bench/", "vulkan/", "GLFW/"}},
      {{"engine/vk", "engine/scene", "engine/render", "engine/occlusion", "engine/present"},
       {"engine/tools/", "engine/app/", "bench/", "generators/bake/"}},
      {{"engine/tools", "bench"}, {"engine/app/"}},
      {{"generators/core"}, {"generators/"}},
  };
  size_t includes = 0;
  for (const Rule& r : rules)
    for (const fs::path& f : sources(r.roots))
      for (const std::string& inc : includes_of(f)) {
        ++includes;
        if (r.roots[0] == "generators/core" && starts_with(inc, "generators/core/")) continue;
        for (const std::string& bad : r.forbidden) EXPECT_FALSE(starts_with(inc, bad)) << rel(f) << " includes " << inc;
      }
  EXPECT_GT(includes, 500u);
}
