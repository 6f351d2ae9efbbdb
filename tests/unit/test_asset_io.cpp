// .glb encode/decode: round trip, determinism, robustness against malformed files.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "generators/asset/asset_io.h"
#include "generators/core/input_error.h"
#include "generators/mesh/mesh_tangents.h"
#include "generators/species/registry.h"
#include "tests/common/small_species.h"

using namespace forest;
using forest::test::kSmallSpecies;
namespace fs = std::filesystem;

namespace {

TreeModel small_model(uint64_t seed = 7) {
  return generate_from_species_text(kSmallSpecies, "small.toml", {seed});
}

// A GLB container around arbitrary JSON and binary chunk.
std::vector<uint8_t> make_glb(const nlohmann::json& j, std::vector<uint8_t> bin) {
  std::string text = j.dump();
  while (text.size() % 4) text.push_back(' ');
  while (bin.size() % 4) bin.push_back(0);
  std::vector<uint8_t> out;
  auto u32 = [&](uint32_t v) {
    uint8_t b[4];
    std::memcpy(b, &v, 4);
    out.insert(out.end(), b, b + 4);
  };
  u32(0x46546C67u);
  u32(2);
  u32(uint32_t(12 + 8 + text.size() + (bin.empty() ? 0 : 8 + bin.size())));
  u32(uint32_t(text.size()));
  u32(0x4E4F534Au);
  out.insert(out.end(), text.begin(), text.end());
  if (!bin.empty()) {
    u32(uint32_t(bin.size()));
    u32(0x004E4942u);
    out.insert(out.end(), bin.begin(), bin.end());
  }
  return out;
}

template <class T>
void append(std::vector<uint8_t>& bin, const std::vector<T>& v) {
  const auto* p = reinterpret_cast<const uint8_t*>(v.data());
  bin.insert(bin.end(), p, p + v.size() * sizeof(T));
  while (bin.size() % 4) bin.push_back(0);
}

// One triangle with indices of the given component type (5121, 5123 or 5125).
std::pair<nlohmann::json, std::vector<uint8_t>> triangle_asset(int index_type,
                                                               std::vector<uint32_t> idx = {0, 1, 2}) {
  std::vector<uint8_t> bin;
  append(bin, std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
  append(bin, std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1});
  append(bin, std::vector<float>{0, 0, 1, 0, 0, 1});
  size_t idx_offset = bin.size();
  if (index_type == 5121) append(bin, std::vector<uint8_t>(idx.begin(), idx.end()));
  if (index_type == 5123) append(bin, std::vector<uint16_t>(idx.begin(), idx.end()));
  if (index_type == 5125) append(bin, idx);
  size_t isize = index_type == 5121 ? 1 : index_type == 5123 ? 2 : 4;
  nlohmann::json j = {
      {"asset", {{"version", "2.0"}}},
      {"buffers", {{{"byteLength", bin.size()}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}},
        {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 36}},
        {{"buffer", 0}, {"byteOffset", 72}, {"byteLength", 24}},
        {{"buffer", 0}, {"byteOffset", idx_offset}, {"byteLength", idx.size() * isize}}}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"},
         {"min", {0, 0, 0}}, {"max", {1, 1, 0}}},
        {{"bufferView", 1}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}},
        {{"bufferView", 2}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}},
        {{"bufferView", 3}, {"componentType", index_type}, {"count", idx.size()}, {"type", "SCALAR"}}}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}}, {"indices", 3}}}}}}},
      {"nodes", {{{"name", "branches"}, {"mesh", 0}}}},
      {"scenes", {{{"nodes", {0}}}}},
      {"scene", 0}};
  return {j, bin};
}

}  // namespace

TEST(AssetIo, RoundTrip) {
  TreeModel m = small_model();
  ASSERT_GT(m.branches.indices.size(), 0u);
  ASSERT_GT(m.leaves.size(), 0u);
  TreeModel d = decode_glb(encode_glb(m), "mem.glb");
  ASSERT_EQ(d.branches.vertices.size(), m.branches.vertices.size());
  EXPECT_EQ(d.branches.indices, m.branches.indices);
  for (size_t i = 0; i < m.branches.vertices.size(); ++i) {
    EXPECT_EQ(d.branches.vertices[i].position, m.branches.vertices[i].position);
    EXPECT_NEAR(glm::length(d.branches.vertices[i].normal - m.branches.vertices[i].normal), 0.0f, 1e-6f);
    EXPECT_EQ(d.branches.vertices[i].uv, m.branches.vertices[i].uv);
  }
  ASSERT_EQ(d.leaf_card.vertices.size(), m.leaf_card.vertices.size());
  EXPECT_EQ(d.leaf_card.indices, m.leaf_card.indices);
  ASSERT_EQ(d.leaves.size(), m.leaves.size());
  for (size_t i = 0; i < m.leaves.size(); ++i) {
    EXPECT_EQ(d.leaves[i].position, m.leaves[i].position);
    EXPECT_NEAR(std::abs(glm::dot(d.leaves[i].rotation, m.leaves[i].rotation)), 1.0f, 1e-6f);
    EXPECT_FLOAT_EQ(d.leaves[i].scale, m.leaves[i].scale);
  }
  EXPECT_EQ(d.bark_color, m.bark_color);
  EXPECT_EQ(d.leaf_color, m.leaf_color);
  EXPECT_EQ(d.bounding_sphere, m.bounding_sphere);
  EXPECT_EQ(d.meta, m.meta);
  EXPECT_EQ(d.meta["method"], "lsystem");
  EXPECT_EQ(d.meta["seed"], 7);
}

TEST(AssetIo, EncodingIsDeterministic) {
  TreeModel m = small_model();
  EXPECT_EQ(encode_glb(m), encode_glb(m));
  EXPECT_EQ(encode_glb(small_model(7)), encode_glb(small_model(7)));
  EXPECT_NE(encode_glb(small_model(7)), encode_glb(small_model(8)));
  std::vector<uint8_t> bytes = encode_glb(m);
  EXPECT_EQ(bytes.size() % 4, 0u);
  EXPECT_EQ(std::memcmp(bytes.data(), "glTF", 4), 0);
}

TEST(AssetIo, LayoutFollowsTheFormat) {
  std::vector<uint8_t> bytes = encode_glb(small_model());
  uint32_t json_len;
  std::memcpy(&json_len, bytes.data() + 12, 4);
  nlohmann::json j = nlohmann::json::parse(bytes.begin() + 20, bytes.begin() + 20 + json_len);
  EXPECT_EQ(j["extensionsUsed"], nlohmann::json::array({"EXT_mesh_gpu_instancing"}));
  EXPECT_EQ(j["extras"]["forest"]["format_version"], 1);
  EXPECT_EQ(j["nodes"][0]["name"], "tree");
  EXPECT_EQ(j["nodes"][0]["children"].size(), 2u);
  for (const auto& v : j["bufferViews"]) {
    EXPECT_EQ(v.value("byteOffset", 0) % 4, 0);
    EXPECT_FALSE(v.contains("byteStride"));
  }
  const auto& leaves = j["nodes"][2];
  EXPECT_EQ(leaves["name"], "leaves");
  const auto& attrs = leaves["extensions"]["EXT_mesh_gpu_instancing"]["attributes"];
  for (const char* a : {"TRANSLATION", "ROTATION", "SCALE"}) {
    int acc = attrs[a];
    EXPECT_FALSE(j["bufferViews"][int(j["accessors"][acc]["bufferView"])].contains("target")) << a;
    EXPECT_EQ(j["accessors"][acc]["componentType"], 5126);
  }
  EXPECT_EQ(j["materials"][1]["doubleSided"], true);
  EXPECT_TRUE(j["accessors"][0].contains("min"));
}

TEST(AssetIo, LodsTextureAndLeafColorsRoundTrip) {
  std::string text = kSmallSpecies;
  text.insert(text.find("[[production]]"), "leaf_color_jitter = 0.3\nleaf_shape = \"lanceolate\"\n");
  TreeModel m = generate_from_species_text(text, "small.toml", {7});
  ASSERT_GE(m.branch_lods.size(), 1u);
  ASSERT_FALSE(m.leaf_texture.rgba.empty());
  bool varied = false;
  for (const LeafPlacement& l : m.leaves) varied = varied || l.color != m.leaves[0].color;
  ASSERT_TRUE(varied);
  std::vector<uint8_t> bytes = encode_glb(m);
  TreeModel d = decode_glb(bytes, "mem.glb");
  // LODs: same meshes, same errors, in level order.
  ASSERT_EQ(d.branch_lods.size(), m.branch_lods.size());
  for (size_t i = 0; i < m.branch_lods.size(); ++i) {
    EXPECT_EQ(d.branch_lods[i].error, m.branch_lods[i].error);
    EXPECT_EQ(d.branch_lods[i].mesh.indices, m.branch_lods[i].mesh.indices);
    ASSERT_EQ(d.branch_lods[i].mesh.vertices.size(), m.branch_lods[i].mesh.vertices.size());
    for (size_t k = 0; k < m.branch_lods[i].mesh.vertices.size(); ++k)
      EXPECT_EQ(d.branch_lods[i].mesh.vertices[k].position, m.branch_lods[i].mesh.vertices[k].position);
  }
  // The leaf texture: lossless PNG.
  EXPECT_EQ(d.leaf_texture.width, m.leaf_texture.width);
  EXPECT_EQ(d.leaf_texture.height, m.leaf_texture.height);
  EXPECT_EQ(d.leaf_texture.rgba, m.leaf_texture.rgba);
  // Per-leaf colors.
  ASSERT_EQ(d.leaves.size(), m.leaves.size());
  for (size_t i = 0; i < m.leaves.size(); ++i) EXPECT_EQ(d.leaves[i].color, m.leaves[i].color);

  // The JSON: LOD meshes tagged in their extras, outside the scene; the leaf material is
  // alpha-masked with the embedded texture; _COLOR_0 is a float VEC3 instance attribute.
  uint32_t json_len;
  std::memcpy(&json_len, bytes.data() + 12, 4);
  nlohmann::json j = nlohmann::json::parse(bytes.begin() + 20, bytes.begin() + 20 + json_len);
  size_t tagged = 0;
  for (const auto& mesh : j["meshes"]) {
    if (!mesh.contains("extras")) continue;
    const auto& tag = mesh["extras"]["forest_lod"];
    ++tagged;
    EXPECT_EQ(mesh["name"], "branches_lod" + std::to_string(int(tag["level"])));
    EXPECT_FLOAT_EQ(float(tag["error"].get<double>()), m.branch_lods[size_t(int(tag["level"])) - 1].error);
  }
  EXPECT_EQ(tagged, m.branch_lods.size());
  for (int child : j["nodes"][0]["children"]) EXPECT_EQ(j["nodes"][child]["name"].get<std::string>().find("lod"), std::string::npos);
  const auto& leaf = j["materials"][1];
  EXPECT_EQ(leaf["name"], "leaf");
  EXPECT_EQ(leaf["alphaMode"], "MASK");
  EXPECT_EQ(leaf.value("alphaCutoff", 0.5), 0.5);  // the glTF default, which tinygltf leaves implicit
  int tex = leaf["pbrMetallicRoughness"]["baseColorTexture"]["index"];
  int img = j["textures"][tex]["source"];
  EXPECT_EQ(j["images"][img]["mimeType"], "image/png");
  EXPECT_TRUE(j["images"][img].contains("bufferView"));
  EXPECT_EQ(leaf["doubleSided"], true);
  const auto& instancing = j["nodes"][2]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"];
  EXPECT_FALSE(instancing.contains("_COLOR"));  // written as three.js reads instance colours
  int color = instancing["_COLOR_0"];
  EXPECT_EQ(j["accessors"][color]["type"], "VEC3");
  EXPECT_EQ(j["accessors"][color]["componentType"], 5126);
  // A model without texture or LODs writes neither.
  TreeModel plain = m;
  plain.branch_lods.clear();
  plain.leaf_texture = Image8{};
  TreeModel p = decode_glb(encode_glb(plain), "plain.glb");
  EXPECT_TRUE(p.branch_lods.empty());
  EXPECT_TRUE(p.leaf_texture.rgba.empty());
}

TEST(AssetIo, AcceptsSmallIndexTypesAndNoLeaves) {
  for (int type : {5121, 5123, 5125}) {
    auto [j, bin] = triangle_asset(type);
    TreeModel m = decode_glb(make_glb(j, bin), "tri.glb");
    EXPECT_EQ(m.branches.indices, std::vector<uint32_t>({0, 1, 2})) << type;
    EXPECT_EQ(m.branches.vertices.size(), 3u);
    EXPECT_TRUE(m.leaves.empty());
    EXPECT_GT(m.bounding_sphere.w, 0.5f);  // computed, since there is no extras.forest
  }
}

TEST(AssetIo, RejectsInconsistentAssets) {
  auto bad = [](auto edit, std::vector<uint32_t> idx = {0, 1, 2}) {
    auto [j, bin] = triangle_asset(5125, idx);
    edit(j);
    EXPECT_THROW(decode_glb(make_glb(j, bin), "bad.glb"), InputError) << j.dump();
  };
  bad([](nlohmann::json&) {}, {0, 1, 3});  // index out of range
  bad([](nlohmann::json& j) { j["accessors"][0]["count"] = 1000; });
  bad([](nlohmann::json& j) { j["accessors"][3]["componentType"] = 5126; });
  bad([](nlohmann::json& j) { j["accessors"][3]["count"] = 2; });  // not triangles
  bad([](nlohmann::json& j) { j["accessors"][0]["type"] = "VEC2"; });
  bad([](nlohmann::json& j) { j["accessors"][1]["count"] = 2; });  // attribute counts differ
  bad([](nlohmann::json& j) { j["bufferViews"][0]["byteOffset"] = 1 << 20; });
  bad([](nlohmann::json& j) { j["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 17; });
  bad([](nlohmann::json& j) { j["meshes"][0]["primitives"][0]["mode"] = 1; });
  bad([](nlohmann::json& j) { j["nodes"][0]["name"] = "trunk"; });  // no branches node
  bad([](nlohmann::json& j) { j["buffers"][0]["uri"] = "/etc/passwd"; });
}

TEST(AssetIo, CorruptBytesNeverCrash) {
  std::vector<uint8_t> good = encode_glb(small_model());
  // Truncation anywhere.
  for (size_t len = 0; len < good.size(); len += (len < 400 ? 1 : 97)) {
    std::vector<uint8_t> cut(good.begin(), good.begin() + std::ptrdiff_t(len));
    EXPECT_THROW(decode_glb(cut, "cut.glb"), InputError) << len;
  }
  // Byte flips: either a clean decode (flip in unread data) or an InputError.
  size_t rejected = 0;
  for (size_t at = 0; at < good.size(); at += (at < 2000 ? 3 : 211)) {
    for (uint8_t mask : {uint8_t(0x01), uint8_t(0x80), uint8_t(0xFF)}) {
      std::vector<uint8_t> b = good;
      b[at] ^= mask;
      try {
        TreeModel m = decode_glb(b, "flip.glb");
        for (uint32_t i : m.branches.indices) ASSERT_LT(i, m.branches.vertices.size());
      } catch (const InputError&) {
        ++rejected;
      }
    }
  }
  EXPECT_GT(rejected, 10u);
  EXPECT_THROW(decode_glb(std::vector<uint8_t>(100, 0), "zeros.glb"), InputError);
}

TEST(AssetIo, FilesAtomicAndErrors) {
  fs::path dir = fs::temp_directory_path() / ("forest_asset_io_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  TreeModel m = small_model();
  fs::path file = dir / "tree.glb";
  save_glb(m, file);
  EXPECT_EQ(load_glb(file).meta, m.meta);
  std::ifstream in(file, std::ios::binary);
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(bytes, encode_glb(m));
  size_t files = 0;
  for (auto& e : fs::directory_iterator(dir)) files += e.is_regular_file();
  EXPECT_EQ(files, 1u);  // no temporary left behind
  save_glb(m, file);     // overwriting works
  EXPECT_THROW(save_glb(m, dir / "missing" / "tree.glb"), InputError);
  EXPECT_THROW(load_glb(dir / "nope.glb"), InputError);
  EXPECT_THROW(load_glb(dir), InputError);
  try {
    load_glb(dir / "nope.glb");
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("nope.glb"), std::string::npos);
  }
  std::ofstream(dir / "junk.glb") << "this is not a glb";
  EXPECT_THROW(load_glb(dir / "junk.glb"), InputError);
  fs::remove_all(dir);
}

namespace {

// The asset's JSON chunk, and the bytes with `from` replaced by `to` padded with spaces to
// the same length (JSON whitespace: the chunk keeps its size).
nlohmann::json json_of(const std::vector<uint8_t>& bytes) {
  uint32_t json_len;
  std::memcpy(&json_len, bytes.data() + 12, 4);
  return nlohmann::json::parse(bytes.begin() + 20, bytes.begin() + 20 + json_len);
}

std::vector<uint8_t> replace_in_json(std::vector<uint8_t> bytes, const std::string& from, std::string to) {
  uint32_t json_len;
  std::memcpy(&json_len, bytes.data() + 12, 4);
  std::string text(bytes.begin() + 20, bytes.begin() + 20 + json_len);
  size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at == std::string::npos || to.size() > from.size()) return bytes;
  to.resize(from.size(), ' ');
  std::copy(to.begin(), to.end(), bytes.begin() + 20 + long(at));
  return bytes;
}

}  // namespace

TEST(AssetIo, BarkTexturesRoundTrip) {
  std::string text = kSmallSpecies;
  text.insert(text.find("[[production]]"), "bark_pattern = \"furrowed\"\n");
  TreeModel m = generate_from_species_text(text, "small.toml", {7});
  ASSERT_EQ(m.bark_texture.width, 256u);
  ASSERT_EQ(m.bark_normal.width, 256u);
  const std::vector<uint8_t> bytes = encode_glb(m);
  TreeModel d = decode_glb(bytes, "mem.glb");
  // Lossless, with the look's colour and the tile size from the material's extras.
  EXPECT_EQ(d.bark_texture.width, m.bark_texture.width);
  EXPECT_EQ(d.bark_texture.rgba, m.bark_texture.rgba);
  EXPECT_EQ(d.bark_normal.rgba, m.bark_normal.rgba);
  EXPECT_EQ(d.bark_color, m.bark_color);
  EXPECT_EQ(d.bark_tile_meters, m.bark_tile_meters);
  EXPECT_EQ(d.bark_tile_meters, 0.5f);

  // The JSON: a white factor (the texture is the colour), the normal map, repeating
  // trilinear samplers, TANGENT on every bark mesh (unit xyz, w = ±1).
  nlohmann::json j = json_of(bytes);
  const auto& bark = j["materials"][0];
  EXPECT_EQ(bark["name"], "bark");
  EXPECT_EQ(bark["pbrMetallicRoughness"].value("baseColorFactor", nlohmann::json::array({1.0, 1.0, 1.0, 1.0})),
            nlohmann::json::array({1.0, 1.0, 1.0, 1.0}));  // tinygltf leaves glTF's default implicit
  for (const nlohmann::json* info : {&bark["pbrMetallicRoughness"]["baseColorTexture"], &bark["normalTexture"]}) {
    const auto& sampler = j["samplers"][int(j["textures"][int((*info)["index"])]["sampler"])];
    EXPECT_EQ(sampler["wrapS"], 10497);  // REPEAT
    EXPECT_EQ(sampler["wrapT"], 10497);
    EXPECT_EQ(sampler["minFilter"], 9987);  // LINEAR_MIPMAP_LINEAR
    EXPECT_EQ(sampler["magFilter"], 9729);  // LINEAR
  }
  EXPECT_EQ(bark["extras"]["forest_bark"]["tile_meters"], 0.5);
  size_t with_tangents = 0;
  for (const auto& mesh : j["meshes"]) {
    const auto& attrs = mesh["primitives"][0]["attributes"];
    if (mesh["name"].get<std::string>().rfind("branches", 0) != 0) continue;
    ASSERT_TRUE(attrs.contains("TANGENT")) << mesh["name"];
    EXPECT_EQ(j["accessors"][int(attrs["TANGENT"])]["type"], "VEC4");
    ++with_tangents;
  }
  EXPECT_EQ(with_tangents, 1 + m.branch_lods.size());
  // Older assets: _COLOR as the instance colour's name, no bark textures.
  TreeModel plain = m;
  plain.bark_texture = plain.bark_normal = Image8{};
  plain.bark_color = glm::vec3(0.3f, 0.2f, 0.1f);
  std::vector<uint8_t> old = replace_in_json(encode_glb(plain), "\"_COLOR_0\"", "\"_COLOR\"");
  EXPECT_FALSE(json_of(old)["materials"][0].contains("extras"));
  TreeModel p = decode_glb(old, "old.glb");
  EXPECT_TRUE(p.bark_texture.rgba.empty());
  EXPECT_TRUE(p.bark_normal.rgba.empty());
  EXPECT_EQ(p.bark_color, plain.bark_color);  // from the factor
  ASSERT_EQ(p.leaves.size(), m.leaves.size());
  for (size_t i = 0; i < m.leaves.size(); ++i) EXPECT_EQ(p.leaves[i].color, m.leaves[i].color);
  // A malformed forest_bark is refused.
  std::vector<uint8_t> bad = replace_in_json(bytes, "\"tile_meters\":0.5", "\"tile_meters\":-1");
  EXPECT_THROW(decode_glb(bad, "bad.glb"), InputError);
}

TEST(AssetIo, BarkTangentsFollowUAndTheNormalMapsUp) {
  TreeModel m = small_model();
  std::vector<glm::vec4> tangents = mesh_tangents(m.branches);
  ASSERT_EQ(tangents.size(), m.branches.vertices.size());
  size_t checked = 0, agree = 0;
  for (size_t t = 0; t + 2 < m.branches.indices.size(); t += 3) {
    const Vertex &a = m.branches.vertices[m.branches.indices[t]], &b = m.branches.vertices[m.branches.indices[t + 1]];
    const glm::vec4 ta = tangents[m.branches.indices[t]];
    EXPECT_NEAR(glm::length(glm::vec3(ta)), 1.0f, 1e-4f);
    EXPECT_NEAR(glm::dot(glm::vec3(ta), a.normal), 0.0f, 1e-4f);
    EXPECT_TRUE(ta.w == 1.0f || ta.w == -1.0f);
    // Along an edge, the tangent frame predicts the uv change: +u along xyz, and −v along
    // the bitangent cross(n, t) · w (the +Y of a glTF normal map).
    // (Vertex tangents are averages over their triangles: count the edges that agree.)
    const glm::vec3 e = b.position - a.position;
    const glm::vec2 du = b.uv - a.uv;
    if (glm::length(e) < 1e-4f || glm::length(du) < 1e-4f) continue;
    const glm::vec3 bitangent = glm::cross(glm::normalize(a.normal), glm::vec3(ta)) * ta.w;
    if (std::abs(du.x) > 0.9f * glm::length(du)) ++checked, agree += glm::dot(e, glm::vec3(ta)) * du.x > 0.0f;
    if (std::abs(du.y) > 0.9f * glm::length(du)) ++checked, agree += glm::dot(e, bitangent) * du.y < 0.0f;
  }
  EXPECT_GT(checked, 100u);
  EXPECT_GE(double(agree), 0.99 * double(checked));
}
