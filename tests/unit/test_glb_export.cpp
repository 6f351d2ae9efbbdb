// forest export's client files (glb_export.h): one file per branch LOD with nothing of the
// engine's in it, leaves instanced or flattened, colours and LOD thresholds where clients
// read them. The clients themselves (three.js, Blender, glTF-Validator) are in
// tests/tools/client_import_test.py.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "generators/asset/asset_io.h"
#include "generators/asset/glb_export.h"
#include "generators/species/registry.h"
#include "tests/common/small_species.h"

using namespace forest;
namespace fs = std::filesystem;

namespace {

// A model as the engine stores it: with a hull and bake data, which must stay out.
TreeModel model_with_engine_data() {
  std::string text = test::kSmallSpecies;  // with leaf colours that vary, and a textured leaf
  text.insert(text.find("[[production]]"), "leaf_color_jitter = 0.3\nleaf_shape = \"lanceolate\"\n");
  TreeModel m = generate_from_species_text(text, "small.toml", {7});
  m.hull = m.leaf_card;  // any drawable mesh: the writer stores it as node "hull"
  return m;
}

std::vector<uint8_t> slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), {}};
}

nlohmann::json gltf_json(const std::vector<uint8_t>& bytes) {
  uint32_t len;
  std::memcpy(&len, bytes.data() + 12, 4);
  return nlohmann::json::parse(bytes.begin() + 20, bytes.begin() + 20 + len);
}

// The floats of an accessor (tightly packed, as the writer makes them).
std::vector<float> floats(const nlohmann::json& j, const std::vector<uint8_t>& bytes, int accessor, int components) {
  uint32_t json_len;
  std::memcpy(&json_len, bytes.data() + 12, 4);
  const uint8_t* bin = bytes.data() + 20 + json_len + 8;
  const auto& a = j["accessors"][accessor];
  const auto& v = j["bufferViews"][int(a["bufferView"])];
  size_t offset = size_t(v.value("byteOffset", 0)) + size_t(a.value("byteOffset", 0));
  std::vector<float> out(a["count"].get<size_t>() * size_t(components));
  std::memcpy(out.data(), bin + offset, out.size() * sizeof(float));
  return out;
}

const nlohmann::json* node_named(const nlohmann::json& j, const std::string& name) {
  for (const auto& n : j["nodes"])
    if (n["name"] == name) return &n;
  return nullptr;
}

class GlbExport : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("forest-export-" + std::to_string(getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

}  // namespace

TEST_F(GlbExport, OneFilePerLevelWithOnlyBarkAndLeaves) {
  TreeModel m = model_with_engine_data();
  ASSERT_GE(m.branch_lods.size(), 1u);
  std::vector<ExportedLod> lods = export_model(m, dir_ / "oak.glb");
  ASSERT_EQ(lods.size(), m.branch_lods.size() + 1);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), std::ptrdiff_t(lods.size()));
  float last_coverage = 2.0f;
  for (size_t i = 0; i < lods.size(); ++i) {
    const fs::path expect = dir_ / (i == 0 ? "oak.glb" : "oak_LOD" + std::to_string(i) + ".glb");
    EXPECT_EQ(lods[i].file, expect);
    std::vector<uint8_t> bytes = slurp(expect);
    nlohmann::json j = gltf_json(bytes);
    // Nothing of the engine's: no hull, no impostor, no bake data, no other LOD meshes.
    EXPECT_FALSE(j.contains("extras")) << i;
    std::vector<std::string> names;
    for (const auto& n : j["nodes"]) names.push_back(n["name"]);
    EXPECT_EQ(names, (std::vector<std::string>{"oak_LOD" + std::to_string(i), "branches", "leaves"})) << i;
    EXPECT_EQ(j["meshes"].size(), 2u) << i;
    EXPECT_EQ(j["scenes"][0]["nodes"], nlohmann::json::array({0}));
    // The level's own bark.
    const Mesh& bark = i == 0 ? m.branches : m.branch_lods[i - 1].mesh;
    int bark_mesh = (*node_named(j, "branches"))["mesh"];
    EXPECT_EQ(size_t(j["accessors"][int(j["meshes"][bark_mesh]["primitives"][0]["indices"])]["count"]),
              bark.indices.size()) << i;
    EXPECT_EQ(lods[i].branch_triangles, bark.indices.size() / 3);
    // Thresholds: level, error, coverage; coarser levels never at larger coverage (a level
    // whose error stays below a pixel at full screen is capped at 1).
    const auto& lod = j["nodes"][0]["extras"]["lod"];
    EXPECT_EQ(lod["level"], i);
    EXPECT_EQ(lod["levels"], lods.size());
    EXPECT_EQ(lod["files"].size(), lods.size());
    float coverage = lod["screen_coverage"];
    EXPECT_LE(coverage, last_coverage) << i;
    EXPECT_GT(coverage, 0.0f);
    last_coverage = coverage;
    if (i > 0) {
      // Where the level may be drawn, its error projects to at most error_pixels.
      float error = lod["error_meters"];
      EXPECT_EQ(error, m.branch_lods[i - 1].error);
      float pixels = error * coverage * 1080.0f / (2.0f * m.bounding_sphere.w);
      EXPECT_LE(pixels, 1.0001f);
      if (coverage < 1.0f) {
        EXPECT_NEAR(pixels, 1.0f, 1e-4f);  // and not needlessly late
      }
    }
  }
  EXPECT_LT(last_coverage, 0.5f);  // the coarsest level is for small trees
}

TEST_F(GlbExport, InstancedLeavesCarryTheirColourAsColor0) {
  TreeModel m = model_with_engine_data();
  export_model(m, dir_ / "t.glb");
  std::vector<uint8_t> bytes = slurp(dir_ / "t.glb");
  nlohmann::json j = gltf_json(bytes);
  const auto& attrs = (*node_named(j, "leaves"))["extensions"]["EXT_mesh_gpu_instancing"]["attributes"];
  EXPECT_EQ(j["accessors"][int(attrs["TRANSLATION"])]["count"], m.leaves.size());
  std::vector<float> c = floats(j, bytes, attrs["_COLOR_0"], 3);
  ASSERT_EQ(c.size(), 3 * m.leaves.size());
  for (size_t i = 0; i < m.leaves.size(); ++i) EXPECT_EQ(c[3 * i + 1], m.leaves[i].color.g);
  EXPECT_FALSE(attrs.contains("_CROWN_DEPTH_POS"));
}

TEST_F(GlbExport, FlattenedLeavesAreOneMeshWithVertexColours) {
  TreeModel m = model_with_engine_data();
  std::vector<ExportedLod> lods = export_model(m, dir_ / "t.glb", {.flatten = true});
  std::vector<uint8_t> bytes = slurp(dir_ / "t.glb");
  nlohmann::json j = gltf_json(bytes);
  EXPECT_FALSE(j.contains("extensionsUsed"));
  const nlohmann::json& leaves = *node_named(j, "leaves");
  EXPECT_FALSE(leaves.contains("extensions"));
  const auto& prim = j["meshes"][int(leaves["mesh"])]["primitives"][0];
  const size_t card_vertices = m.leaf_card.vertices.size();
  EXPECT_EQ(j["accessors"][int(prim["indices"])]["count"], m.leaves.size() * m.leaf_card.indices.size());
  EXPECT_EQ(lods[0].leaf_triangles, m.leaves.size() * m.leaf_card.indices.size() / 3);
  std::vector<float> pos = floats(j, bytes, prim["attributes"]["POSITION"], 3);
  std::vector<float> col = floats(j, bytes, prim["attributes"]["COLOR_0"], 3);
  ASSERT_EQ(pos.size(), 3 * m.leaves.size() * card_vertices);
  ASSERT_EQ(col.size(), pos.size());
  // COLOR_0 is a unit colour (the spec's range); factor × COLOR_0 is the engine's colour.
  const auto& material = j["materials"][int(prim["material"])];
  std::vector<float> factor = material["pbrMetallicRoughness"]["baseColorFactor"];
  for (float c : col) {
    EXPECT_GE(c, 0.0f);
    EXPECT_LE(c, 1.0f);
  }
  for (size_t l = 0; l < m.leaves.size(); l += 7) {
    const LeafPlacement& leaf = m.leaves[l];
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(factor[size_t(k)] * col[3 * l * card_vertices + size_t(k)], m.leaf_color[k] * leaf.color[k], 1e-5f)
          << "leaf " << l;
    // Each card's corners are placed by the leaf's transform.
    for (size_t v = 0; v < card_vertices; ++v) {
      glm::vec3 expect = leaf.position + glm::normalize(leaf.rotation) * (m.leaf_card.vertices[v].position * leaf.scale);
      const float* p = &pos[3 * (l * card_vertices + v)];
      EXPECT_NEAR(glm::length(glm::vec3(p[0], p[1], p[2]) - expect), 0.0f, 1e-5f) << "leaf " << l;
    }
  }
}

TEST_F(GlbExport, DeterministicBytes) {
  TreeModel m = model_with_engine_data();
  for (bool flatten : {false, true}) {
    export_model(m, dir_ / "a.glb", {.flatten = flatten});
    std::vector<uint8_t> lod0 = slurp(dir_ / "a.glb"), lod1 = slurp(dir_ / "a_LOD1.glb");
    export_model(m, dir_ / "a.glb", {.flatten = flatten});
    EXPECT_EQ(slurp(dir_ / "a.glb"), lod0);
    EXPECT_EQ(slurp(dir_ / "a_LOD1.glb"), lod1);
  }
}
