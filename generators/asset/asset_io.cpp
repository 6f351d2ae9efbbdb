// glTF 2.0 binary I/O through tinygltf. Layout of an asset:
//   scene 0 -> node "tree" -> children "branches" (mesh "branches", material "bark")
//                                      "leaves"   (mesh "leaf_card", material "leaf",
//                                                  EXT_mesh_gpu_instancing T/R/S accessors
//                                                  and _COLOR: per-leaf color multiplier)
//   nodes "branches_lod1", "branches_lod2", ... (meshes of the same names, material "bark",
//     mesh extras {"forest_lod": {"level": i, "error": meters}}): the simplified branch LODs.
//     They are not in the scene, so a generic viewer shows LOD0 only; decode_glb finds them
//     by their extras.
//   material "leaf": baseColorTexture = the leaf texture (PNG in the binary chunk),
//     alphaMode MASK, alphaCutoff 0.5 (glTF's default, so tinygltf writes it implicitly),
//     double sided
//   root extras.forest = TreeModel::meta
// One buffer, one tightly packed buffer view per accessor (so no byteStride anywhere).
// tinygltf and stb are compiled here, once for the whole program. Debian puts stb in
// /usr/include/stb/, where tiny_gltf.h does not look, so stb is included first by path.
#define TINYGLTF_IMPLEMENTATION
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define TINYGLTF_NO_INCLUDE_STB_IMAGE
#define TINYGLTF_NO_INCLUDE_STB_IMAGE_WRITE
#include "generators/asset/asset_io.h"

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>
#include <tiny_gltf.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "generators/core/input_error.h"
#include "generators/core/limits.h"
#include "generators/mesh/mesher.h"

namespace forest {

namespace {

constexpr const char* kInstancing = "EXT_mesh_gpu_instancing";

// ---- JSON <-> tinygltf::Value (extras) ---------------------------------------------------

tinygltf::Value to_value(const nlohmann::json& j) {
  using V = tinygltf::Value;
  switch (j.type()) {
    case nlohmann::json::value_t::object: {
      V::Object o;
      for (auto it = j.begin(); it != j.end(); ++it) o.emplace(it.key(), to_value(it.value()));
      return V(std::move(o));
    }
    case nlohmann::json::value_t::array: {
      V::Array a;
      for (const auto& e : j) a.push_back(to_value(e));
      return V(std::move(a));
    }
    case nlohmann::json::value_t::string: return V(j.get<std::string>());
    case nlohmann::json::value_t::boolean: return V(j.get<bool>());
    case nlohmann::json::value_t::number_integer:
    case nlohmann::json::value_t::number_unsigned: {
      // tinygltf integers are 32-bit; larger ones travel as doubles (exact up to 2^53).
      if (j.is_number_unsigned()) {
        uint64_t u = j.get<uint64_t>();
        if (u <= uint64_t(std::numeric_limits<int>::max())) return V(int(u));
        return V(double(u));
      }
      int64_t i = j.get<int64_t>();
      if (i >= std::numeric_limits<int>::min() && i <= std::numeric_limits<int>::max())
        return V(int(i));
      return V(double(i));
    }
    case nlohmann::json::value_t::number_float: return V(j.get<double>());
    default: return V();
  }
}

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

// ---- encoding ---------------------------------------------------------------------------

struct Writer {
  tinygltf::Model model;
  std::vector<unsigned char> bin;

  // Appends a tightly packed buffer view, 4-byte aligned. target 0: none (instancing data).
  int add_view(const void* data, size_t bytes, int target) {
    while (bin.size() % 4) bin.push_back(0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = bin.size();
    view.byteLength = bytes;
    view.target = target;
    const auto* p = static_cast<const unsigned char*>(data);
    bin.insert(bin.end(), p, p + bytes);
    model.bufferViews.push_back(view);
    return int(model.bufferViews.size() - 1);
  }

  // Float accessor of `comps` components per element (type VEC2/VEC3/VEC4).
  int add_floats(const std::vector<float>& values, int comps, int target, bool with_bounds) {
    tinygltf::Accessor a;
    a.bufferView = add_view(values.data(), values.size() * sizeof(float), target);
    a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    a.count = values.size() / size_t(comps);
    a.type = comps == 2 ? TINYGLTF_TYPE_VEC2 : comps == 3 ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_VEC4;
    if (with_bounds) {  // exact float extrema, as the validator checks them
      a.minValues.assign(size_t(comps), std::numeric_limits<double>::infinity());
      a.maxValues.assign(size_t(comps), -std::numeric_limits<double>::infinity());
      for (size_t i = 0; i < values.size(); ++i) {
        size_t c = i % size_t(comps);
        a.minValues[c] = std::min(a.minValues[c], double(values[i]));
        a.maxValues[c] = std::max(a.maxValues[c], double(values[i]));
      }
    }
    model.accessors.push_back(a);
    return int(model.accessors.size() - 1);
  }

  int add_indices(const std::vector<uint32_t>& indices) {
    tinygltf::Accessor a;
    a.bufferView = add_view(indices.data(), indices.size() * sizeof(uint32_t),
                            TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    a.count = indices.size();
    a.type = TINYGLTF_TYPE_SCALAR;
    model.accessors.push_back(a);
    return int(model.accessors.size() - 1);
  }

  // texture < 0: untextured and opaque; else alpha-masked with that base color texture.
  int add_material(const std::string& name, glm::vec3 color, bool double_sided, int texture = -1) {
    tinygltf::Material m;
    m.name = name;
    m.pbrMetallicRoughness.baseColorFactor = {color.r, color.g, color.b, 1.0};
    m.pbrMetallicRoughness.metallicFactor = 0.0;
    m.pbrMetallicRoughness.roughnessFactor = 1.0;
    m.doubleSided = double_sided;
    if (texture >= 0) {
      m.pbrMetallicRoughness.baseColorTexture.index = texture;
      m.alphaMode = "MASK";
      m.alphaCutoff = 0.5;
    }
    model.materials.push_back(m);
    return int(model.materials.size() - 1);
  }

  // An RGBA8 image as a PNG in the binary chunk, with a trilinear, clamped sampler.
  int add_texture(const std::string& name, const Image8& img) {
    std::vector<unsigned char> png;
    auto sink = [](void* ctx, void* data, int size) {
      auto* out = static_cast<std::vector<unsigned char>*>(ctx);
      const auto* p = static_cast<const unsigned char*>(data);
      out->insert(out->end(), p, p + size);
    };
    if (!stbi_write_png_to_func(sink, &png, int(img.width), int(img.height), 4, img.rgba.data(),
                                int(img.width) * 4))
      throw std::runtime_error("cannot encode the " + name + " texture as PNG");
    tinygltf::Image image;
    image.name = name;
    image.mimeType = "image/png";
    image.bufferView = add_view(png.data(), png.size(), 0);
    model.images.push_back(image);
    tinygltf::Sampler sampler;
    sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
    sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
    sampler.wrapS = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
    sampler.wrapT = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
    model.samplers.push_back(sampler);
    tinygltf::Texture texture;
    texture.name = name;
    texture.sampler = int(model.samplers.size() - 1);
    texture.source = int(model.images.size() - 1);
    model.textures.push_back(texture);
    return int(model.textures.size() - 1);
  }

  int add_mesh(const std::string& name, const Mesh& mesh, int material) {
    std::vector<float> pos, nrm, uv;
    for (const Vertex& v : mesh.vertices) {
      pos.insert(pos.end(), {v.position.x, v.position.y, v.position.z});
      glm::vec3 n = glm::length(v.normal) > 0.0f ? glm::normalize(v.normal) : glm::vec3(0, 1, 0);
      nrm.insert(nrm.end(), {n.x, n.y, n.z});
      uv.insert(uv.end(), {v.uv.x, v.uv.y});
    }
    tinygltf::Primitive prim;
    prim.attributes["POSITION"] = add_floats(pos, 3, TINYGLTF_TARGET_ARRAY_BUFFER, true);
    prim.attributes["NORMAL"] = add_floats(nrm, 3, TINYGLTF_TARGET_ARRAY_BUFFER, false);
    prim.attributes["TEXCOORD_0"] = add_floats(uv, 2, TINYGLTF_TARGET_ARRAY_BUFFER, false);
    prim.indices = add_indices(mesh.indices);
    prim.material = material;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    tinygltf::Mesh m;
    m.name = name;
    m.primitives.push_back(prim);
    model.meshes.push_back(m);
    return int(model.meshes.size() - 1);
  }
};

bool drawable(const Mesh& m) { return !m.vertices.empty() && !m.indices.empty(); }

// ---- decoding ---------------------------------------------------------------------------

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
    Image8 out;
    if (!mat) return out;
    int t = mat->pbrMetallicRoughness.baseColorTexture.index;
    if (t < 0) return out;
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
    std::vector<float> color;  // optional per-leaf color multiplier
    if (attrs.Has("_COLOR")) {
      color = floats(index("_COLOR"), TINYGLTF_TYPE_VEC3, "_COLOR");
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
// Embedded images (buffer views) are decoded by stb_image to RGBA8, within a size limit.
bool load_image(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                const unsigned char* bytes, int size, void*) {
  constexpr int kMaxSide = 4096;
  int w = 0, h = 0, comp = 0;
  if (size <= 0 || !stbi_info_from_memory(bytes, size, &w, &h, &comp) || w <= 0 || h <= 0 ||
      w > kMaxSide || h > kMaxSide) {
    if (err) *err = "image " + std::to_string(index) + ": not a readable PNG/JPEG of at most 4096^2 pixels";
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

}  // namespace

std::vector<uint8_t> encode_glb(const TreeModel& tree) {
  Writer w;
  tinygltf::Model& m = w.model;
  m.asset.version = "2.0";
  m.asset.generator = "forest";

  tinygltf::Node root;
  root.name = "tree";
  tinygltf::Node branches;
  branches.name = "branches";
  int bark = -1;
  if (drawable(tree.branches)) {
    bark = w.add_material("bark", tree.bark_color, false);
    branches.mesh = w.add_mesh("branches", tree.branches, bark);
  }
  m.nodes.push_back(root);
  m.nodes.push_back(branches);
  m.nodes[0].children.push_back(1);

  if (!tree.leaves.empty() && drawable(tree.leaf_card)) {
    tinygltf::Node leaves;
    leaves.name = "leaves";
    int texture = tree.leaf_texture.rgba.empty() ? -1 : w.add_texture("leaf", tree.leaf_texture);
    leaves.mesh = w.add_mesh("leaf_card", tree.leaf_card, w.add_material("leaf", tree.leaf_color, true, texture));
    std::vector<float> t, r, s, c;
    for (const LeafPlacement& l : tree.leaves) {
      t.insert(t.end(), {l.position.x, l.position.y, l.position.z});
      glm::quat q = glm::normalize(l.rotation);
      r.insert(r.end(), {q.x, q.y, q.z, q.w});
      s.insert(s.end(), {l.scale, l.scale, l.scale});
      c.insert(c.end(), {l.color.r, l.color.g, l.color.b});
    }
    tinygltf::Value::Object attrs;
    attrs["TRANSLATION"] = tinygltf::Value(w.add_floats(t, 3, 0, false));
    attrs["ROTATION"] = tinygltf::Value(w.add_floats(r, 4, 0, false));
    attrs["SCALE"] = tinygltf::Value(w.add_floats(s, 3, 0, false));
    attrs["_COLOR"] = tinygltf::Value(w.add_floats(c, 3, 0, false));
    tinygltf::Value::Object ext;
    ext["attributes"] = tinygltf::Value(std::move(attrs));
    leaves.extensions[kInstancing] = tinygltf::Value(std::move(ext));
    m.nodes.push_back(leaves);
    m.nodes[0].children.push_back(int(m.nodes.size() - 1));
    m.extensionsUsed.push_back(kInstancing);
  }

  for (size_t i = 0; i < tree.branch_lods.size(); ++i) {
    const MeshLod& lod = tree.branch_lods[i];
    if (!drawable(lod.mesh)) continue;
    if (bark < 0) bark = w.add_material("bark", tree.bark_color, false);
    std::string name = "branches_lod" + std::to_string(i + 1);
    tinygltf::Node node;
    node.name = name;
    node.mesh = w.add_mesh(name, lod.mesh, bark);
    m.meshes[size_t(node.mesh)].extras = to_value(
        nlohmann::json{{"forest_lod", {{"level", i + 1}, {"error", lod.error}}}});
    m.nodes.push_back(node);
  }

  // The metaball hull (bake): occlusion sample points live in extras.forest.hull_samples.
  if (drawable(tree.hull)) {
    tinygltf::Node hull;
    hull.name = "hull";
    hull.mesh = w.add_mesh("hull", tree.hull, w.add_material("hull", glm::vec3(0.5f), false));
    m.nodes.push_back(hull);
  }

  tinygltf::Scene scene;
  scene.name = "forest";
  scene.nodes.push_back(0);
  m.scenes.push_back(scene);
  m.defaultScene = 0;

  while (w.bin.size() % 4) w.bin.push_back(0);
  tinygltf::Buffer buffer;
  buffer.data = std::move(w.bin);
  m.buffers.push_back(std::move(buffer));

  tinygltf::Value::Object extras;
  extras["forest"] = to_value(tree.meta);
  m.extras = tinygltf::Value(std::move(extras));

  tinygltf::TinyGLTF gltf;
  std::ostringstream out;
  if (!gltf.WriteGltfSceneToStream(&m, out, /*prettyPrint=*/false, /*writeBinary=*/true))
    throw std::runtime_error("tinygltf failed to serialize the asset");
  std::string bytes = out.str();
  return std::vector<uint8_t>(bytes.begin(), bytes.end());
}

TreeModel decode_glb(std::span<const uint8_t> bytes, const std::string& name) {
  // The container is checked before tinygltf sees it: header, declared length, chunk sizes.
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

  tinygltf::TinyGLTF gltf;
  tinygltf::FsCallbacks fs{no_file_exists, no_expand, no_read, no_write, nullptr};
  gltf.SetFsCallbacks(fs);
  gltf.SetImageLoader(load_image, nullptr);
  tinygltf::Model model;
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
  tree.branches = r.mesh(*branches, &tree.bark_color);
  if (leaves) {
    tree.leaf_card = r.mesh(*leaves, &tree.leaf_color);
    tree.leaves = r.instances(*leaves);
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
    for (const char* key : {"species", "method", "priority"})
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
  return tree;
}

void write_file_atomic(const std::filesystem::path& path, std::span<const uint8_t> bytes) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path dir = path.parent_path();
  if (!dir.empty() && !fs::is_directory(dir, ec))
    throw InputError(path.string(), 0, "", "directory " + dir.string() + " does not exist");
  fs::path tmp = path;
  tmp += ".tmp-" + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(path.string(), 0, "", "cannot write (permission denied or not a directory?)");
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    out.flush();
    if (!out) {
      out.close();
      fs::remove(tmp, ec);
      throw InputError(path.string(), 0, "", "write failed (disk full?)");
    }
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    std::error_code ec2;
    fs::remove(tmp, ec2);
    throw InputError(path.string(), 0, "", "cannot rename temporary file: " + ec.message());
  }
}

void save_glb(const TreeModel& model, const std::filesystem::path& path) {
  std::vector<uint8_t> bytes = encode_glb(model);
  write_file_atomic(path, bytes);
}

TreeModel load_glb(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(path.string(), 0, "", std::filesystem::exists(path, ec) ? "not a regular file" : "file not found");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), 0, "", "cannot open file");
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(path.string(), 0, "", "read error");
  return decode_glb(bytes, path.string());
}

}  // namespace forest
