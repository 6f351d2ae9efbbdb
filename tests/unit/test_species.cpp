// Species files: the presets, their budgets, metadata, determinism and input errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "generators/bake/asset_io.h"
#include "generators/common/input_error.h"
#include "generators/methods/methods.h"
#include "generators/tree/mesher.h"

using namespace forest;
namespace fs = std::filesystem;

namespace {

fs::path species_dir() { return fs::path(FOREST_SOURCE_DIR) / "scenes" / "species"; }

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

const char* kBase = R"(method = "lsystem"
seed = 3
iterations = 2
axiom = "X"
step = 0.5
[[production]]
predecessor = "X"
successor = "F[+X]F[-X]X"
)";

// Expects generating `text` to fail with a message naming the file, the line and the key.
void expect_error(const std::string& text, int line, const std::string& key) {
  try {
    generate_from_species_text(text, "oak.toml");
    ADD_FAILURE() << "no error for:\n" << text;
  } catch (const InputError& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("oak.toml:" + std::to_string(line) + ":"), std::string::npos) << msg;
    EXPECT_NE(msg.find(key), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

// kBase with one line inserted after `method` (line 2).
std::string with_line(const std::string& line) {
  std::string t = kBase;
  t.insert(t.find('\n') + 1, line + "\n");
  return t;
}

}  // namespace

TEST(Species, MethodIdsAndDefaultText) {
  std::vector<std::string> ids = method_ids();
  EXPECT_NE(std::find(ids.begin(), ids.end(), "lsystem"), ids.end());
  EXPECT_EQ(default_species_text("lsystem"), read_text(species_dir() / "fig2_1.toml"));
  EXPECT_THROW(default_species_text("particle-flow-nonexistent"), InputError);
  TreeModel m = generate_from_species_text(default_species_text("lsystem"), "fig2_1.toml");
  EXPECT_EQ(m.meta["node_count"], 24385);  // 24384 F after 7 iterations, plus the root
}

TEST(Species, EveryPresetGenerates) {
  size_t presets = 0;
  for (const auto& e : fs::directory_iterator(species_dir())) {
    if (e.path().extension() != ".toml") continue;
    ++presets;
    TreeModel m = generate_from_species(e.path());
    EXPECT_GT(m.branches.indices.size(), 0u) << e.path();
    EXPECT_GT(m.leaves.size(), 0u) << e.path();
    EXPECT_EQ(m.meta["species"], e.path().stem().string());
  }
  EXPECT_GE(presets, 3u);
}

TEST(Species, DemoPresetsFitTheBudget) {
  for (const char* name : {"broadleaf", "conifer"}) {
    TreeModel m = generate_from_species(species_dir() / (std::string(name) + ".toml"));
    size_t tris = m.branches.indices.size() / 3;
    double height = m.meta["height"];
    EXPECT_LE(tris, 5000u) << name;  // LOD0, forks joined
    EXPECT_GE(tris, 1000u) << name;
    EXPECT_LE(m.leaves.size(), 1500u) << name;
    EXPECT_GE(m.leaves.size(), 300u) << name;
    EXPECT_GE(height, 6.0) << name;
    EXPECT_LE(height, 15.0) << name;
    // A tree stands on the origin and grows up.
    EXPECT_GT(m.bounding_sphere.y, 2.0f) << name;
    EXPECT_LT(std::abs(m.bounding_sphere.x), 0.5f * m.bounding_sphere.w) << name;
  }
}

TEST(Species, MetadataDescribesTheModel) {
  TreeModel m = generate_from_species_text(kBase, "dir/bush.toml", {123});
  const auto& meta = m.meta;
  EXPECT_EQ(meta["format_version"], 1);
  EXPECT_EQ(meta["generator"], "forest");
  EXPECT_EQ(meta["method"], "lsystem");
  EXPECT_EQ(meta["species"], "bush");
  EXPECT_EQ(meta["seed"], 123);  // the override, not the file's 3
  EXPECT_EQ(meta["parameters"]["seed"], 3);
  EXPECT_EQ(meta["parameters"]["axiom"], "X");
  EXPECT_EQ(meta["parameters"]["production"][0]["successor"], "F[+X]F[-X]X");
  EXPECT_EQ(meta["leaf_count"], m.leaves.size());
  EXPECT_EQ(meta["node_count"], 9);  // 2 + 3 * 2 F after two iterations, plus the root
  ASSERT_EQ(meta["bounding_sphere"].size(), 4u);
  EXPECT_FLOAT_EQ(float(meta["bounding_sphere"][3].get<double>()), m.bounding_sphere.w);
  EXPECT_EQ(m.bounding_sphere, bounding_sphere(m.branches, m.leaf_card, m.leaves));
  float top = 0.0f;
  for (const Vertex& v : m.branches.vertices) top = std::max(top, v.position.y);
  EXPECT_GE(float(meta["height"].get<double>()), top);
}

TEST(Species, SeedsAreDeterministic) {
  const fs::path broadleaf = species_dir() / "broadleaf.toml";
  auto bytes = [&](uint64_t seed) { return encode_glb(generate_from_species(broadleaf, {seed})); };
  EXPECT_EQ(bytes(7), bytes(7));
  EXPECT_NE(bytes(7), bytes(8));
  // Without an override the file's seed is used.
  EXPECT_EQ(encode_glb(generate_from_species(broadleaf)), bytes(11));
}

TEST(Species, ErrorsNameFileLineAndKey) {
  expect_error(with_line("colour = 3"), 2, "colour");                       // unknown key
  expect_error(with_line("angle = \"wide\""), 2, "angle");                  // wrong type
  expect_error(with_line("step_jitter = nan"), 2, "step_jitter");           // NaN
  expect_error(with_line("leaf_size = -0.1"), 2, "leaf_size");              // negative
  expect_error(with_line("tip_radius = inf"), 2, "tip_radius");
  std::string t = kBase;
  t.replace(t.find("seed = 3"), 8, "seed = -1");
  expect_error(t, 2, "seed");
  t.replace(t.find("seed = -1"), 9, "seed = 1.5");
  expect_error(t, 2, "seed");
  expect_error(with_line("bark_color = [1, 2]"), 2, "bark_color");
  expect_error(with_line("bark_color = [0.5, 0.5, 1.5]"), 2, "bark_color");
  expect_error(with_line("ring_sides_min = 6\nring_sides_max = 4"), 3, "ring_sides_max");
  t = kBase;
  t.replace(t.find("iterations = 2"), 14, "iterations = 13");
  expect_error(t, 3, "iterations");                                         // too many
  t = kBase;
  t.replace(t.find("axiom = \"X\""), 11, "axiom = \"F[X\"");
  expect_error(t, 4, "axiom");                                              // brackets
  expect_error(std::string(kBase) + "weight = -2\n", 9, "weight");
  expect_error(std::string(kBase) + "wieght = 2\n", 9, "wieght");
  expect_error(std::string(kBase) + "[[production]]\npredecessor = \"XY\"\nsuccessor = \"F\"\n", 10,
               "predecessor");
  expect_error(std::string(kBase) + "[[production]]\npredecessor = \"F\"\nsuccessor = \"F(x)\"\n", 11,
               "successor");
  // Explosion: F -> FFFF for 12 iterations is 16 M symbols.
  expect_error("method = \"lsystem\"\niterations = 12\naxiom = \"F\"\n[[production]]\n"
               "predecessor = \"F\"\nsuccessor = \"FFFF\"\n", 2, "iterations");
  expect_error("method = \"lsystem\"\naxiom = \"F\"\nstep = [1\n", 3, "");   // malformed TOML
  expect_error("method = \"lsystem\"\nseed = 1\n", 1, "iterations");        // missing key
  expect_error("method = \"lsystem\"\niterations = 1\n", 1, "axiom");
  expect_error("method = \"oak-magic\"\naxiom = \"F\"\n", 1, "method");     // unknown method
  expect_error("axiom = \"F\"\nmethod = \"lsystem\"\n", 1, "axiom");        // method not first
  EXPECT_THROW(generate_from_species(species_dir() / "does-not-exist.toml"), InputError);
}
