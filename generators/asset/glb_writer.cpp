// TreeModel -> glTF 2.0 binary (encode_glb) through tinygltf. Layout of an asset:
//   scene 0 -> node "tree" -> children "branches" (mesh "branches", material "bark")
//                                      "leaves"   (mesh "leaf_card", material "leaf",
//                                                  EXT_mesh_gpu_instancing T/R/S accessors
//                                                  and _COLOR_0: per-leaf color multiplier; baked:
//                                                  _CROWN_DEPTH_POS / _NEG, crown depths)
//   nodes "branches_lod1", "branches_lod2", ... (meshes of the same names, material "bark",
//     mesh extras {"forest_lod": {"level": i, "error": meters}}): the simplified branch LODs.
//     They are not in the scene, so a generic viewer shows LOD0 only; decode_glb finds them
//     by their extras.
//   node "hull" (mesh "hull", material "hull"): the metaball hull of a baked model, not in
//     the scene
//   material "leaf": baseColorTexture = the leaf texture (PNG in the binary chunk),
//     alphaMode MASK, alphaCutoff 0.5 (glTF's default, so tinygltf writes it implicitly),
//     double sided
//   material "bark", when the model has bark textures: baseColorFactor white,
//     baseColorTexture = the bark albedo (the whole colour), normalTexture = the bark normal
//     map, both with a repeating trilinear sampler, TANGENT on the bark meshes; extras
//     {"forest_bark": {"color": bark_color, "tile_meters": ...}} keep the look's colour and
//     the tile size. Without textures: baseColorFactor = bark_color, as before.
//   material "impostor", when baked (TreeModel::impostor, no mesh uses it): baseColorTexture =
//     the albedo atlas (alpha = coverage, MASK, double sided); extras {"forest_impostor":
//     {"grid", "view_size", "normal_depth_texture": texture index, "q": PR_SIZES numbers, "cutoff"}}
//   root extras.forest = TreeModel::meta plus TreeModel::bake (bake_to_json, bake_data.cpp)
// One buffer, one tightly packed buffer view per accessor (so no byteStride anywhere).
#include "generators/asset/asset_io.h"

#include <stb/stb_image_write.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "generators/asset/bake_data.h"
#include "generators/mesh/mesh_tangents.h"

namespace forest {

namespace {

constexpr const char* kInstancing = "EXT_mesh_gpu_instancing";

// JSON -> tinygltf::Value (extras).
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

  // The trilinear sampler with this wrap mode (one per mode).
  int sampler(int wrap) {
    for (size_t i = 0; i < model.samplers.size(); ++i)
      if (model.samplers[i].wrapS == wrap) return int(i);
    tinygltf::Sampler sampler;
    sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
    sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
    sampler.wrapS = sampler.wrapT = wrap;
    model.samplers.push_back(sampler);
    return int(model.samplers.size() - 1);
  }

  // An RGBA8 image as a PNG in the binary chunk (`channels` 4, or 3 for an opaque one), with
  // a trilinear sampler that clamps (leaf) or repeats (bark).
  int add_texture(const std::string& name, const Image8& img, int wrap = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE,
                  int channels = 4) {
    std::vector<unsigned char> png;
    auto sink = [](void* ctx, void* data, int size) {
      auto* out = static_cast<std::vector<unsigned char>*>(ctx);
      const auto* p = static_cast<const unsigned char*>(data);
      out->insert(out->end(), p, p + size);
    };
    std::vector<uint8_t> rgb;
    const uint8_t* pixels = img.rgba.data();
    if (channels == 3) {
      for (size_t i = 0; i < img.rgba.size(); i += 4) rgb.insert(rgb.end(), {img.rgba[i], img.rgba[i + 1], img.rgba[i + 2]});
      pixels = rgb.data();
    }
    if (!stbi_write_png_to_func(sink, &png, int(img.width), int(img.height), channels, pixels,
                                int(img.width) * channels))
      throw std::runtime_error("cannot encode the " + name + " texture as PNG");
    tinygltf::Image image;
    image.name = name;
    image.mimeType = "image/png";
    image.bufferView = add_view(png.data(), png.size(), 0);
    model.images.push_back(image);
    tinygltf::Texture texture;
    texture.name = name;
    texture.sampler = sampler(wrap);
    texture.source = int(model.images.size() - 1);
    model.textures.push_back(texture);
    return int(model.textures.size() - 1);
  }

  // The bark material: textured when the model has bark textures (see the top).
  int add_bark_material(const TreeModel& tree) {
    if (tree.bark_texture.rgba.empty()) return add_material("bark", tree.bark_color, false);
    int m = add_material("bark", glm::vec3(1.0f), false);
    int albedo = add_texture("bark", tree.bark_texture, TINYGLTF_TEXTURE_WRAP_REPEAT, 3);
    tinygltf::Material& mat = model.materials[size_t(m)];
    mat.pbrMetallicRoughness.baseColorTexture.index = albedo;
    if (!tree.bark_normal.rgba.empty())
      mat.normalTexture.index = add_texture("bark_normal", tree.bark_normal, TINYGLTF_TEXTURE_WRAP_REPEAT, 3);
    const glm::vec3 c = tree.bark_color;
    mat.extras = to_value(nlohmann::json{
        {"forest_bark", {{"color", {c.r, c.g, c.b}}, {"tile_meters", tree.bark_tile_meters}}}});
    return m;
  }

  // with_tangents: also TANGENT (mesh_tangents), for a normal-mapped material.
  // colors: also COLOR_0 (linear RGB per vertex).
  int add_mesh(const std::string& name, const Mesh& mesh, int material, bool with_tangents = false,
               const std::vector<float>* colors = nullptr) {
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
    if (with_tangents) {
      std::vector<float> tan;
      for (const glm::vec4& t : mesh_tangents(mesh)) tan.insert(tan.end(), {t.x, t.y, t.z, t.w});
      prim.attributes["TANGENT"] = add_floats(tan, 4, TINYGLTF_TARGET_ARRAY_BUFFER, false);
    }
    if (colors) prim.attributes["COLOR_0"] = add_floats(*colors, 3, TINYGLTF_TARGET_ARRAY_BUFFER, false);
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

// Every leaf card placed in model space, one mesh, with each leaf's colour on its vertices:
// what a client without EXT_mesh_gpu_instancing can draw.
Mesh flattened_leaves(const TreeModel& tree, std::vector<float>& colors) {
  Mesh out;
  out.vertices.reserve(tree.leaves.size() * tree.leaf_card.vertices.size());
  out.indices.reserve(tree.leaves.size() * tree.leaf_card.indices.size());
  for (const LeafPlacement& l : tree.leaves) {
    const glm::quat q = glm::normalize(l.rotation);
    const uint32_t base = uint32_t(out.vertices.size());
    for (Vertex v : tree.leaf_card.vertices) {
      v.position = l.position + q * (v.position * l.scale);
      v.normal = q * v.normal;
      out.vertices.push_back(v);
      colors.insert(colors.end(), {l.color.r, l.color.g, l.color.b});
    }
    for (uint32_t i : tree.leaf_card.indices) out.indices.push_back(base + i);
  }
  return out;
}

}  // namespace

std::vector<uint8_t> encode_glb(const TreeModel& tree, const GlbOptions& options) {
  Writer w;
  tinygltf::Model& m = w.model;
  m.asset.version = "2.0";
  m.asset.generator = "forest";

  tinygltf::Node root;
  root.name = options.root_name;
  if (!options.root_extras.is_null()) root.extras = to_value(options.root_extras);
  tinygltf::Node branches;
  branches.name = "branches";
  int bark = -1;
  const bool bark_tangents = !tree.bark_texture.rgba.empty() && !tree.bark_normal.rgba.empty();
  if (drawable(tree.branches)) {
    bark = w.add_bark_material(tree);
    branches.mesh = w.add_mesh("branches", tree.branches, bark, bark_tangents);
  }
  m.nodes.push_back(root);
  m.nodes.push_back(branches);
  m.nodes[0].children.push_back(1);

  if (!tree.leaves.empty() && drawable(tree.leaf_card) && options.flatten_leaves) {
    tinygltf::Node leaves;
    leaves.name = "leaves";
    int texture = tree.leaf_texture.rgba.empty() ? -1 : w.add_texture("leaf", tree.leaf_texture);
    std::vector<float> colors;
    Mesh flat = flattened_leaves(tree, colors);
    // COLOR_0 must stay within 0..1, the per-leaf multipliers reach a little above 1: the
    // largest moves into the material's factor (colour = factor × texture × COLOR_0).
    float k = 1.0f;
    for (float c : colors) k = std::max(k, c);
    for (float& c : colors) c /= k;
    glm::vec3 factor = glm::min(tree.leaf_color * k, glm::vec3(1.0f));
    leaves.mesh = w.add_mesh("leaves", flat, w.add_material("leaf", factor, true, texture), false, &colors);
    m.nodes.push_back(leaves);
    m.nodes[0].children.push_back(int(m.nodes.size() - 1));
  } else if (!tree.leaves.empty() && drawable(tree.leaf_card)) {
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
    attrs["_COLOR_0"] = tinygltf::Value(w.add_floats(c, 3, 0, false));  // three.js: instance colour
    if (const std::optional<CrownLight>& crown = tree.bake.crown) {  // baked crown depths, metres
      if (crown->depths.size() != tree.leaves.size())
        throw std::logic_error("encode_glb: " + std::to_string(crown->depths.size()) + " crown depths for " +
                               std::to_string(tree.leaves.size()) + " leaves");
      std::vector<float> pos, neg;
      for (const CrownCube& d : crown->depths) {
        pos.insert(pos.end(), {d[0], d[2], d[4]});
        neg.insert(neg.end(), {d[1], d[3], d[5]});
      }
      attrs["_CROWN_DEPTH_POS"] = tinygltf::Value(w.add_floats(pos, 3, 0, false));
      attrs["_CROWN_DEPTH_NEG"] = tinygltf::Value(w.add_floats(neg, 3, 0, false));
    }
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
    if (bark < 0) bark = w.add_bark_material(tree);
    std::string name = "branches_lod" + std::to_string(i + 1);
    tinygltf::Node node;
    node.name = name;
    node.mesh = w.add_mesh(name, lod.mesh, bark, bark_tangents);
    m.meshes[size_t(node.mesh)].extras = to_value(
        nlohmann::json{{"forest_lod", {{"level", i + 1}, {"error", lod.error}}}});
    m.nodes.push_back(node);
  }

  // The metaball hull (bake); its occlusion samples travel in extras.forest (bake_to_json).
  if (drawable(tree.hull)) {
    tinygltf::Node hull;
    hull.name = "hull";
    hull.mesh = w.add_mesh("hull", tree.hull, w.add_material("hull", glm::vec3(0.5f), false));
    m.nodes.push_back(hull);
  }

  // The impostor atlases: a material no mesh of the scene uses (impostor_bake.h).
  if (tree.impostor.present()) {
    const Impostor& imp = tree.impostor;
    int albedo = w.add_texture("impostor_albedo", imp.albedo);
    int material = w.add_material("impostor", glm::vec3(1.0f), true, albedo);
    int normal_depth = w.add_texture("impostor_normal_depth", imp.normal_depth);
    m.materials[size_t(material)].extras = to_value(nlohmann::json{
        {"forest_impostor",
         {{"grid", IMPOSTOR_GRID}, {"view_size", IMPOSTOR_VIEW_SIZE}, {"normal_depth_texture", normal_depth},
          {"q", imp.q}, {"cutoff", imp.cutoff}}}});
  }

  tinygltf::Scene scene;
  scene.name = options.scene_name;
  scene.nodes.push_back(0);
  m.scenes.push_back(scene);
  m.defaultScene = 0;

  while (w.bin.size() % 4) w.bin.push_back(0);
  tinygltf::Buffer buffer;
  buffer.data = std::move(w.bin);
  m.buffers.push_back(std::move(buffer));

  nlohmann::json forest = tree.meta;
  if (!options.forest_extras) {
    // A client file: no extras.forest (the bake data is the engine's, not a viewer's).
  } else if (tree.bake.crown && !(!tree.leaves.empty() && drawable(tree.leaf_card))) {
    BakeData bake = tree.bake;  // no leaves node to carry the depths: κ alone would be refused
    bake.crown.reset();
    bake_to_json(bake, forest);
  } else {
    bake_to_json(tree.bake, forest);
  }
  if (options.forest_extras) {
    tinygltf::Value::Object extras;
    extras["forest"] = to_value(forest);
    m.extras = tinygltf::Value(std::move(extras));
  }

  tinygltf::TinyGLTF gltf;
  std::ostringstream out;
  if (!gltf.WriteGltfSceneToStream(&m, out, /*prettyPrint=*/false, /*writeBinary=*/true))
    throw std::runtime_error("tinygltf failed to serialize the asset");
  std::string bytes = out.str();
  return std::vector<uint8_t>(bytes.begin(), bytes.end());
}

}  // namespace forest
