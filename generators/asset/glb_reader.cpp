// glTF 2.0 binary -> TreeModel (decode_glb) through tinygltf; the layout is described in
// glb_writer.cpp. Everything read is checked: indices and sizes against their buffers,
// numbers finite, counts within limits, extras.forest's bake keys by bake_from_json
// (bake_data.cpp); anything else is an InputError naming the file.
#include "generators/asset/asset_io.h"

#include <stb/stb_image.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <cstring>
#include <optional>

#include "generators/asset/bake_data.h"
#include "generators/core/input_error.h"
#include "generators/core/limits.h"
#include "generators/mesh/mesher.h"

namespace forest {

namespace {

constexpr const char* kInstancing = "EXT_mesh_gpu_instancing";

// tinygltf::Value (extras) -> JSON.
nlohmann::json to_json(const tinygltf::Value& v) {
  switch (v.Type()) {
    case tinygltf::OBJECT_TYPE: {
      nlohmann::json o = nlohmann::json::object();
      for (const std::string& k : v.Keys()) o[k] = to_json(v.Get(k));
      return o;
    }
    case tinygltf::ARRAY_TYPE: {
      nlohmann::json a = nlohmann::json::array();
      for (size_t i = 0; i < v.ArrayLen(); ++i) a.push_back(to_json(v.Get(int(i))));
      return a;
    }
    case tinygltf::STRING_TYPE: return v.Get<std::string>();
    case tinygltf::BOOL_TYPE: return v.Get<bool>();
    case tinygltf::INT_TYPE: return v.Get<int>();
    case tinygltf::REAL_TYPE: return v.Get<double>();
    default: return nullptr;
  }
}

struct Reader {
  const tinygltf::Model& model;
  const std::string& name;

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(name, 0, "", "malformed glTF asset: " + what);
  }

  const tinygltf::Accessor& accessor(int index, const char* what) const {
    if (index < 0 || size_t(index) >= model.accessors.size())
      fail(std::string(what) + ": accessor index out of range");
    return model.accessors[size_t(index)];
  }

  // The bytes of element i of an accessor are at base + i * stride; checks that all of them
  // lie inside the buffer. Returns base pointer and stride.
  std::pair<const unsigned char*, size_t> locate(const tinygltf::Accessor& a, size_t elem_size,
                                                 const char* what) const {
    if (a.sparse.isSparse) fail(std::string(what) + ": sparse accessors are not supported");
    if (a.bufferView < 0 || size_t(a.bufferView) >= model.bufferViews.size())
      fail(std::string(what) + ": buffer view index out of range");
    const tinygltf::BufferView& v = model.bufferViews[size_t(a.bufferView)];
    if (v.buffer < 0 || size_t(v.buffer) >= model.buffers.size())
      fail(std::string(what) + ": buffer index out of range");
    const std::vector<unsigned char>& data = model.buffers[size_t(v.buffer)].data;
    if (v.byteOffset > data.size() || v.byteLength > data.size() - v.byteOffset)
      fail(std::string(what) + ": buffer view exceeds its buffer");
    size_t stride = v.byteStride ? v.byteStride : elem_size;
    if (stride < elem_size) fail(std::string(what) + ": byteStride smaller than an element");
    if (a.count == 0) return {data.data(), stride};
    if (a.byteOffset > v.byteLength || elem_size > v.byteLength - a.byteOffset ||
        (a.count - 1) > (v.byteLength - a.byteOffset - elem_size) / stride)
      fail(std::string(what) + ": accessor exceeds its buffer view");
    return {data.data() + v.byteOffset + a.byteOffset, stride};
  }

  std::vector<float> floats(int index, int type, const char* what) const {
    const tinygltf::Accessor& a = accessor(index, what);
    if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || a.type != type || a.normalized)
      fail(std::string(what) + ": expected a float " + (type == TINYGLTF_TYPE_VEC2 ? "VEC2" : type == TINYGLTF_TYPE_VEC3 ? "VEC3" : "VEC4") + " accessor");
    size_t comps = size_t(tinygltf::GetNumComponentsInType(uint32_t(type)));
    auto [base, stride] = locate(a, comps * sizeof(float), what);
    std::vector<float> out(a.count * comps);
    for (size_t i = 0; i < a.count; ++i) {
      std::memcpy(&out[i * comps], base + i * stride, comps * sizeof(float));
      for (size_t c = 0; c < comps; ++c)
        if (!std::isfinite(out[i * comps + c])) fail(std::string(what) + ": non-finite value");
    }
    return out;
  }

  std::vector<uint32_t> indices(int index, size_t vertex_count, const char* what) const {
    const tinygltf::Accessor& a = accessor(index, what);
    size_t size = 0;
    switch (a.componentType) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: size = 1; break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: size = 2; break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: size = 4; break;
      default: fail(std::string(what) + ": indices must be unsigned byte, short or int");
    }
    if (a.type != TINYGLTF_TYPE_SCALAR) fail(std::string(what) + ": indices must be SCALAR");
    if (a.count % 3) fail(std::string(what) + ": index count is not a multiple of 3");
    auto [base, stride] = locate(a, size, what);
    std::vector<uint32_t> out(a.count);
    for (size_t i = 0; i < a.count; ++i) {
      const unsigned char* p = base + i * stride;
      uint32_t v = 0;
      if (size == 1) v = p[0];
      if (size == 2) { uint16_t s; std::memcpy(&s, p, 2); v = s; }
      if (size == 4) std::memcpy(&v, p, 4);
      if (v >= vertex_count) fail(std::string(what) + ": index out of range");
      out[i] = v;
    }
    return out;
  }

  // The first triangle primitive of a node's mesh: vertices, indices and material color.
  Mesh mesh(const tinygltf::Node& node, glm::vec3* color) const {
    if (node.mesh < 0) return Mesh{};
    if (size_t(node.mesh) >= model.meshes.size()) fail("node '" + node.name + "': mesh index out of range");
    return mesh(model.meshes[size_t(node.mesh)], color);
  }

  // The material of a mesh's first primitive, or nullptr.
  const tinygltf::Material* material(const tinygltf::Mesh& m) const {
    if (m.primitives.empty()) return nullptr;
    int i = m.primitives[0].material;
    return i >= 0 && size_t(i) < model.materials.size() ? &model.materials[size_t(i)] : nullptr;
  }

  // The base color texture of a material as RGBA8; empty when it has none.
  Image8 base_color_texture(const tinygltf::Material* mat) const {
    return mat ? texture(mat, mat->pbrMetallicRoughness.baseColorTexture.index) : Image8{};
  }

  // Texture t of a material as RGBA8; empty when there is none (no material, t < 0).
  Image8 texture(const tinygltf::Material* mat, int t) const {
    Image8 out;
    if (!mat || t < 0) return out;
    if (size_t(t) >= model.textures.size()) fail("material '" + mat->name + "': texture index out of range");
    int src = model.textures[size_t(t)].source;
    if (src < 0 || size_t(src) >= model.images.size()) fail("texture " + std::to_string(t) + ": image index out of range");
    const tinygltf::Image& img = model.images[size_t(src)];
    if (img.component != 4 || img.bits != 8 || img.width <= 0 || img.height <= 0 ||
        img.image.size() != size_t(img.width) * size_t(img.height) * 4)
      fail("image " + std::to_string(src) + ": not decoded as RGBA8");
    out.width = uint32_t(img.width);
    out.height = uint32_t(img.height);
    out.rgba = img.image;
    return out;
  }

  Mesh mesh(const tinygltf::Mesh& m, glm::vec3* color) const {
    Mesh out;
    if (m.primitives.empty()) fail("mesh '" + m.name + "' has no primitives");
    const tinygltf::Primitive& prim = m.primitives[0];
    if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1)
      fail("mesh '" + m.name + "': only triangle lists are supported");
    auto attr = [&](const char* key) {
      auto it = prim.attributes.find(key);
      if (it == prim.attributes.end()) fail("mesh '" + m.name + "' lacks " + key);
      return it->second;
    };
    std::vector<float> pos = floats(attr("POSITION"), TINYGLTF_TYPE_VEC3, "POSITION");
    std::vector<float> nrm = floats(attr("NORMAL"), TINYGLTF_TYPE_VEC3, "NORMAL");
    std::vector<float> uv = floats(attr("TEXCOORD_0"), TINYGLTF_TYPE_VEC2, "TEXCOORD_0");
    size_t n = pos.size() / 3;
    if (nrm.size() / 3 != n || uv.size() / 2 != n)
      fail("mesh '" + m.name + "': attribute counts differ");
    out.vertices.resize(n);
    for (size_t i = 0; i < n; ++i) {
      out.vertices[i].position = {pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]};
      out.vertices[i].normal = {nrm[3 * i], nrm[3 * i + 1], nrm[3 * i + 2]};
      out.vertices[i].uv = {uv[2 * i], uv[2 * i + 1]};
    }
    if (prim.indices < 0) fail("mesh '" + m.name + "' is not indexed");
    out.indices = indices(prim.indices, n, "indices");
    if (prim.material >= 0 && size_t(prim.material) < model.materials.size()) {
      const auto& f = model.materials[size_t(prim.material)].pbrMetallicRoughness.baseColorFactor;
      // Finite and within float range: narrowing a larger double is undefined behavior.
      auto ok = [](double x) { return std::isfinite(x) && std::abs(x) <= 1e6; };
      if (f.size() == 4 && ok(f[0]) && ok(f[1]) && ok(f[2]))
        *color = glm::vec3(float(f[0]), float(f[1]), float(f[2]));
    }
    return out;
  }

  // The bark material's textures and, from its extras.forest_bark, the look's colour (the
  // factor is white when the texture holds the colour) and the tile size.
  void bark(const tinygltf::Node& node, TreeModel& tree) const {
    if (node.mesh < 0 || size_t(node.mesh) >= model.meshes.size()) return;
    const tinygltf::Material* mat = material(model.meshes[size_t(node.mesh)]);
    if (!mat) return;
    tree.bark_texture = texture(mat, mat->pbrMetallicRoughness.baseColorTexture.index);
    tree.bark_normal = texture(mat, mat->normalTexture.index);
    if (!mat->extras.IsObject() || !mat->extras.Has("forest_bark")) return;
    const nlohmann::json b = to_json(mat->extras.Get("forest_bark"));
    auto number = [](const nlohmann::json& j) {
      return j.is_number() && std::isfinite(j.get<double>()) && j.get<double>() >= 0.0 && j.get<double>() <= 1e6;
    };
    const char* what = "material 'bark': extras.forest_bark needs a color of 3 numbers in [0, 1e6] and tile_meters";
    if (!b.is_object() || !b.contains("color") || !b["color"].is_array() || b["color"].size() != 3 ||
        !std::all_of(b["color"].begin(), b["color"].end(), number) || !b.contains("tile_meters") ||
        !number(b["tile_meters"]))
      fail(what);
    tree.bark_color = glm::vec3(float(b["color"][0].get<double>()), float(b["color"][1].get<double>()),
                                float(b["color"][2].get<double>()));
    tree.bark_tile_meters = float(b["tile_meters"].get<double>());
  }

  // The impostor (material "impostor", extras.forest_impostor; glb_writer.cpp): both atlases
  // IMPOSTOR_ATLAS_SIZE square, the grid of this build, PR_SIZES qualities in [0, 1].
  Impostor impostor() const {
    Impostor out;
    const tinygltf::Material* mat = nullptr;
    for (const tinygltf::Material& m : model.materials)
      if (m.name == "impostor" && m.extras.IsObject() && m.extras.Has("forest_impostor")) mat = &m;
    if (!mat) return out;
    const nlohmann::json j = to_json(mat->extras.Get("forest_impostor"));
    const char* what = "material 'impostor': extras.forest_impostor";
    auto integer = [&](const char* key) {
      if (!j.is_object() || !j.contains(key) || !j[key].is_number_integer())
        fail(std::string(what) + "." + key + " is not an integer");
      return j[key].get<int64_t>();
    };
    if (integer("grid") != IMPOSTOR_GRID || integer("view_size") != IMPOSTOR_VIEW_SIZE)
      fail(std::string(what) + ": a grid of " + std::to_string(integer("grid")) + " views of " +
           std::to_string(integer("view_size")) + " px, this build reads " + std::to_string(IMPOSTOR_GRID) + " of " +
           std::to_string(IMPOSTOR_VIEW_SIZE) + " (re-bake the model)");
    int64_t nd = integer("normal_depth_texture");
    if (nd < 0 || nd >= int64_t(model.textures.size())) fail(std::string(what) + ".normal_depth_texture out of range");
    if (!j.contains("q") || !j["q"].is_array() || j["q"].size() != PR_SIZES)
      fail(std::string(what) + ".q needs " + std::to_string(PR_SIZES) + " numbers");
    for (const nlohmann::json& q : j["q"]) {
      if (!q.is_number() || !std::isfinite(q.get<double>()) || q.get<double>() < 0.0 || q.get<double>() > 1.0)
        fail(std::string(what) + ".q: each a number in [0, 1]");
      out.q.push_back(float(q.get<double>()));
    }
    if (!j.contains("cutoff") || !j["cutoff"].is_number() || !std::isfinite(j["cutoff"].get<double>()) ||
        j["cutoff"].get<double>() <= 0.0 || j["cutoff"].get<double>() >= 1.0)
      fail(std::string(what) + ".cutoff: a number in (0, 1)");
    out.cutoff = float(j["cutoff"].get<double>());
    out.albedo = texture(mat, mat->pbrMetallicRoughness.baseColorTexture.index);
    out.normal_depth = texture(mat, int(nd));
    for (const Image8* img : {&out.albedo, &out.normal_depth})
      if (img->width != IMPOSTOR_ATLAS_SIZE || img->height != IMPOSTOR_ATLAS_SIZE)
        fail(std::string(what) + ": atlases must be " + std::to_string(IMPOSTOR_ATLAS_SIZE) + " px square");
    return out;
  }

  std::vector<LeafPlacement> instances(const tinygltf::Node& node) const {
    std::vector<LeafPlacement> out;
    auto ext = node.extensions.find(kInstancing);
    if (ext == node.extensions.end()) return out;
    const tinygltf::Value& attrs = ext->second.Get("attributes");
    if (!attrs.IsObject()) fail(std::string(kInstancing) + ": no attributes");
    auto index = [&](const char* key) {
      const tinygltf::Value& v = attrs.Get(key);
      if (!v.IsNumber()) fail(std::string(kInstancing) + ": missing " + key);
      return v.GetNumberAsInt();
    };
    // Refuse absurd leaf counts before reading (and allocating) them.
    size_t declared = accessor(index("TRANSLATION"), "TRANSLATION").count;
    if (declared > kMaxLeavesPerModel)
      fail(std::to_string(declared) + " leaves, more than the limit of " + std::to_string(kMaxLeavesPerModel) +
           " per model");
    std::vector<float> t = floats(index("TRANSLATION"), TINYGLTF_TYPE_VEC3, "TRANSLATION");
    std::vector<float> r = floats(index("ROTATION"), TINYGLTF_TYPE_VEC4, "ROTATION");
    std::vector<float> s = floats(index("SCALE"), TINYGLTF_TYPE_VEC3, "SCALE");
    size_t n = t.size() / 3;
    if (r.size() / 4 != n || s.size() / 3 != n) fail("instance attribute counts differ");
    std::vector<float> color;  // optional per-leaf color multiplier: _COLOR_0 (or _COLOR, older assets)
    for (const char* key : {"_COLOR_0", "_COLOR"})
      if (color.empty() && attrs.Has(key)) {
        color = floats(index(key), TINYGLTF_TYPE_VEC3, key);
        if (color.size() / 3 != n) fail("instance attribute counts differ");
      }
    out.resize(n);
    for (size_t i = 0; i < n; ++i) {
      out[i].position = {t[3 * i], t[3 * i + 1], t[3 * i + 2]};
      glm::quat q(r[4 * i + 3], r[4 * i], r[4 * i + 1], r[4 * i + 2]);  // glTF xyzw
      float len = glm::length(q);
      if (!(len > 1e-6f)) fail("ROTATION: zero quaternion");
      out[i].rotation = q / len;
      out[i].scale = (s[3 * i] + s[3 * i + 1] + s[3 * i + 2]) / 3.0f;  // cards scale uniformly
      if (!color.empty()) out[i].color = {color[3 * i], color[3 * i + 1], color[3 * i + 2]};
    }
    return out;
  }

  // The baked crown depths (_CROWN_DEPTH_POS / _NEG, both or neither), one per leaf, each
  // finite and in [0, kMaxCrownDepthOnLoad]. nullopt when absent.
  std::optional<std::vector<CrownCube>> crown_depths(const tinygltf::Node& node, size_t leaf_count) const {
    auto ext = node.extensions.find(kInstancing);
    if (ext == node.extensions.end()) return std::nullopt;
    const tinygltf::Value& attrs = ext->second.Get("attributes");
    const char* keys[2] = {"_CROWN_DEPTH_POS", "_CROWN_DEPTH_NEG"};
    bool has[2] = {attrs.Has(keys[0]), attrs.Has(keys[1])};
    auto refuse = [&](const char* key, const std::string& what) {
      throw InputError(name, 0, std::string("EXT_mesh_gpu_instancing.") + key, what);
    };
    if (has[0] != has[1]) refuse(has[0] ? keys[1] : keys[0], "missing: the crown depth attributes come together");
    if (!has[0]) return std::nullopt;
    std::vector<CrownCube> out(leaf_count);
    for (int side = 0; side < 2; ++side) {
      const tinygltf::Value& v = attrs.Get(keys[side]);
      if (!v.IsNumber()) refuse(keys[side], "expected an accessor index");
      std::vector<float> d = floats(v.GetNumberAsInt(), TINYGLTF_TYPE_VEC3, keys[side]);
      if (d.size() / 3 != leaf_count)
        refuse(keys[side], std::to_string(d.size() / 3) + " depths for " + std::to_string(leaf_count) + " leaves");
      for (size_t i = 0; i < d.size(); ++i) {
        if (!(d[i] >= 0.0f && d[i] <= kMaxCrownDepthOnLoad))  // also NaN (floats() refuses it first)
          refuse(keys[side], "leaf " + std::to_string(i / 3) + ": expected a depth in [0, " +
                                 std::to_string(kMaxCrownDepthOnLoad) + "] m, got " + std::to_string(d[i]));
        out[i / 3][2 * (i % 3) + size_t(side)] = d[i];
      }
    }
    return out;
  }
};

// File access is refused while decoding: an asset is self-contained, and a malformed one
// must not make us read arbitrary paths named in its JSON.
bool no_file_exists(const std::string&, void*) { return false; }
std::string no_expand(const std::string& s, void*) { return s; }
bool no_read(std::vector<unsigned char>*, std::string* err, const std::string&, void*) {
  if (err) *err = "external files are not supported";
  return false;
}
bool no_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err = "writing files is not supported";
  return false;
}
// True when `bytes` is a PNG with an empty IDAT chunk. stb_image copies such a chunk into a
// buffer it has not allocated yet (memcpy from a null pointer, undefined behaviour), so
// those are refused before it sees them; a PNG writer never emits one.
bool png_with_empty_idat(const unsigned char* bytes, size_t size) {
  static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (size < 8 || std::memcmp(bytes, kSignature, 8) != 0) return false;
  for (size_t at = 8; at + 8 <= size;) {
    uint32_t length = uint32_t(bytes[at]) << 24 | uint32_t(bytes[at + 1]) << 16 | uint32_t(bytes[at + 2]) << 8 |
                      uint32_t(bytes[at + 3]);
    if (std::memcmp(bytes + at + 4, "IDAT", 4) == 0 && length == 0) return true;
    if (std::memcmp(bytes + at + 4, "IEND", 4) == 0) return false;
    at += 12 + size_t(length);
  }
  return false;
}

// Embedded images (buffer views) are decoded by stb_image to RGBA8, within a size limit.
// `model` is the asset being loaded: tinygltf hands over a buffer view's bytes without
// checking that the view lies inside its buffer, so that is checked here (a view reaching
// past its buffer would make stb_image read past the allocation).
bool load_image(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                const unsigned char* bytes, int size, void* model) {
  bool inside = false;
  for (const tinygltf::Buffer& b : static_cast<const tinygltf::Model*>(model)->buffers) {
    auto begin = reinterpret_cast<uintptr_t>(b.data.data()), at = reinterpret_cast<uintptr_t>(bytes);
    if (!b.data.empty() && at >= begin && at < begin + b.data.size() && size >= 0 &&
        uintptr_t(size) <= begin + b.data.size() - at)
      inside = true;
  }
  if (!inside) {
    if (err) *err = "image " + std::to_string(index) + ": its buffer view reaches past its buffer";
    return false;
  }
  if (size > 0 && png_with_empty_idat(bytes, size_t(size))) {
    if (err) *err = "image " + std::to_string(index) + ": a PNG with an empty IDAT chunk";
    return false;
  }
  int w = 0, h = 0, comp = 0;
  if (size <= 0 || !stbi_info_from_memory(bytes, size, &w, &h, &comp) || w <= 0 || h <= 0 ||
      w > kMaxGlbImageSide || h > kMaxGlbImageSide) {
    if (err) *err = "image " + std::to_string(index) + ": not a readable PNG/JPEG of at most " + std::to_string(kMaxGlbImageSide) + "^2 pixels";
    return false;
  }
  unsigned char* pixels = stbi_load_from_memory(bytes, size, &w, &h, &comp, 4);
  if (!pixels) {
    if (err) *err = "image " + std::to_string(index) + ": " + stbi_failure_reason();
    return false;
  }
  image->width = w;
  image->height = h;
  image->component = 4;
  image->bits = 8;
  image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  image->image.assign(pixels, pixels + size_t(w) * size_t(h) * 4);
  stbi_image_free(pixels);
  return true;
}

// The container is checked before tinygltf sees it: header, declared length, chunk sizes.
void check_container(std::span<const uint8_t> bytes, const std::string& name) {
  auto u32 = [&](size_t at) {
    uint32_t v;
    std::memcpy(&v, bytes.data() + at, 4);
    return v;
  };
  if (bytes.size() < 20 || std::memcmp(bytes.data(), "glTF", 4) != 0)
    throw InputError(name, 0, "", "not a glTF binary (.glb) file");
  if (u32(4) != 2) throw InputError(name, 0, "", "unsupported glTF binary version");
  if (u32(8) != bytes.size())
    throw InputError(name, 0, "", "truncated or padded: header length " + std::to_string(u32(8)) +
                                      " != file size " + std::to_string(bytes.size()));
  size_t json_len = u32(12);
  if (u32(16) != 0x4E4F534Au || json_len > bytes.size() - 20)
    throw InputError(name, 0, "", "malformed glTF binary: bad JSON chunk");
  size_t at = 20 + json_len;
  if (at < bytes.size()) {
    if (bytes.size() - at < 8) throw InputError(name, 0, "", "malformed glTF binary: bad chunk");
    size_t bin_len = u32(at);
    if (u32(at + 4) != 0x004E4942u || bin_len > bytes.size() - at - 8)
      throw InputError(name, 0, "", "malformed glTF binary: bad BIN chunk");
  }
}

}  // namespace

TreeModel decode_glb(std::span<const uint8_t> bytes, const std::string& name) {
  check_container(bytes, name);

  tinygltf::TinyGLTF gltf;
  tinygltf::FsCallbacks fs{no_file_exists, no_expand, no_read, no_write, nullptr};
  gltf.SetFsCallbacks(fs);
  tinygltf::Model model;
  gltf.SetImageLoader(load_image, &model);
  std::string err, warn;
  bool ok = false;
  try {
    ok = gltf.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), unsigned(bytes.size()), "");
  } catch (const std::exception& e) {
    err = e.what();
  }
  if (!ok) throw InputError(name, 0, "", "malformed glTF asset: " + (err.empty() ? std::string("unknown error") : err));

  Reader r{model, name};
  TreeModel tree;
  tree.leaf_card = Mesh{};
  const tinygltf::Node* branches = nullptr;
  const tinygltf::Node* leaves = nullptr;
  const tinygltf::Node* hull = nullptr;
  for (const tinygltf::Node& n : model.nodes) {
    if (n.name == "branches" && !branches) branches = &n;
    if (n.name == "leaves" && !leaves) leaves = &n;
    if (n.name == "hull" && !hull) hull = &n;
  }
  if (!branches) r.fail("no node named 'branches'");
  std::optional<std::vector<CrownCube>> crown_depths;
  tree.branches = r.mesh(*branches, &tree.bark_color);
  r.bark(*branches, tree);
  if (leaves) {
    tree.leaf_card = r.mesh(*leaves, &tree.leaf_color);
    tree.leaves = r.instances(*leaves);
    crown_depths = r.crown_depths(*leaves, tree.leaves.size());
    if (leaves->mesh >= 0) tree.leaf_texture = r.base_color_texture(r.material(model.meshes[size_t(leaves->mesh)]));
  }
  if (hull) {
    glm::vec3 unused;
    tree.hull = r.mesh(*hull, &unused);
  }
  // Branch LODs: the meshes tagged extras.forest_lod, by level.
  std::vector<std::pair<int, MeshLod>> lods;
  for (const tinygltf::Mesh& mesh : model.meshes) {
    if (!mesh.extras.IsObject() || !mesh.extras.Has("forest_lod")) continue;
    nlohmann::json tag = to_json(mesh.extras.Get("forest_lod"));
    if (!tag.is_object() || !tag.contains("level") || !tag["level"].is_number_integer() ||
        !tag.contains("error") || !tag["error"].is_number() || !std::isfinite(tag["error"].get<double>()) ||
        tag["error"].get<double>() < 0.0)
      r.fail("mesh '" + mesh.name + "': extras.forest_lod needs an integer level and an error >= 0");
    MeshLod lod;
    glm::vec3 unused;
    lod.mesh = r.mesh(mesh, &unused);
    lod.error = float(tag["error"].get<double>());
    lods.emplace_back(tag["level"].get<int>(), std::move(lod));
  }
  std::stable_sort(lods.begin(), lods.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (auto& [level, lod] : lods) tree.branch_lods.push_back(std::move(lod));
  if (model.extras.IsObject() && model.extras.Has("forest")) {
    tree.meta = to_json(model.extras.Get("forest"));
    if (!tree.meta.is_object()) r.fail("extras.forest is not an object");
    // Keys the tools read back from a loaded asset: a wrong type is bad input here, not an
    // exception from deep inside a command later.
    for (const char* key : {"species", "method"})
      if (tree.meta.contains(key) && !tree.meta[key].is_string())
        r.fail(std::string("extras.forest.") + key + " is not a string");
    if (tree.meta.contains("seed") && !(tree.meta["seed"].is_number_integer() && tree.meta["seed"].get<int64_t>() >= 0))
      r.fail("extras.forest.seed is not an integer >= 0");
    if (tree.meta.contains("height") && !tree.meta["height"].is_number())
      r.fail("extras.forest.height is not a number");
  }
  const nlohmann::json* bs = tree.meta.contains("bounding_sphere") ? &tree.meta["bounding_sphere"] : nullptr;
  bool have_sphere = bs && bs->is_array() && bs->size() == 4;
  if (have_sphere)
    for (const auto& e : *bs)  // within float range: narrowing a larger double is undefined
      have_sphere = have_sphere && e.is_number() && std::isfinite(e.get<double>()) && std::abs(e.get<double>()) <= 1e9;
  if (have_sphere && (*bs)[3].get<double>() >= 0.0)
    tree.bounding_sphere = glm::vec4(float((*bs)[0].get<double>()), float((*bs)[1].get<double>()),
                                     float((*bs)[2].get<double>()), float((*bs)[3].get<double>()));
  else
    tree.bounding_sphere = bounding_sphere(tree.branches, tree.leaf_card, tree.leaves);
  // Last, so that the checks above also see assets whose bake data is refused.
  tree.bake = bake_from_json(tree.meta, name);  // takes the bake keys out of meta
  // κ in extras.forest and the per-leaf depths come together.
  if (bool(crown_depths) != bool(tree.bake.crown))
    throw InputError(name, 0, crown_depths ? "extras.forest.crown_extinction" : "EXT_mesh_gpu_instancing._CROWN_DEPTH_POS",
                     crown_depths ? "missing: the leaves carry crown depths" : "missing: extras.forest.crown_extinction is set");
  if (crown_depths) tree.bake.crown->depths = std::move(*crown_depths);
  tree.impostor = r.impostor();
  return tree;
}

}  // namespace forest
