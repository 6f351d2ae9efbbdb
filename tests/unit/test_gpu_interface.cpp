// The GPU interface of shaders/gpu_types.h checked against the compiled shaders, not only
// restated: every .spv the build produced is reflected with spirv-cross (--reflect, JSON), and
//  - every struct shared with GLSL: size (array stride, block size or push-constant extent)
//    = sizeof, every member's offset = offsetof, its GLSL type, array length and strides match
//    the C++ member, by name, both ways;
//  - every descriptor binding a shader declares exists in the C++ set layout it is used with
//    (the renderer's: the union of its passes' Binding lists; the depth pyramid's and the
//    present pass's), with the same descriptor type, count and a stage that covers it;
//  - push-constant blocks: the struct and size the C++ pipeline layout pushes;
//  - specialization constants: the SPEC_* ids; vertex inputs: the ATTR_* locations and the
//    formats of vk::vertex_attributes().
// A struct, binding, spec constant or attribute declared in C++ that no shader uses is a
// failure too (stale declarations would otherwise pass unchecked).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/occlusion/depth_pyramid.h"
#include "engine/present/present.h"
#include "engine/render/renderer.h"
#include "engine/vk/pipelines.h"
#include "gpu_types.h"

#ifndef FOREST_SHADER_DIR
#error "FOREST_SHADER_DIR (the build's compiled .spv files) must be defined (tests/CMakeLists.txt)"
#endif
#ifndef FOREST_SPIRV_CROSS
#error "FOREST_SPIRV_CROSS (path of spirv-cross) must be defined (tests/CMakeLists.txt)"
#endif

using namespace forest;
using namespace forest::gpu;
using json = nlohmann::json;
namespace fs = std::filesystem;

namespace {

// ---- the C++ side: name -> offsetof per struct ------------------------------------------

// GLSL spelling of a C++ member type (its element type for arrays).
template <class T> struct Glsl;
template <> struct Glsl<float> { static constexpr const char* name = "float"; };
template <> struct Glsl<uint32_t> { static constexpr const char* name = "uint"; };
template <> struct Glsl<int32_t> { static constexpr const char* name = "int"; };
template <> struct Glsl<vec2> { static constexpr const char* name = "vec2"; };
template <> struct Glsl<ivec2> { static constexpr const char* name = "ivec2"; };
template <> struct Glsl<vec4> { static constexpr const char* name = "vec4"; };
template <> struct Glsl<uvec4> { static constexpr const char* name = "uvec4"; };
template <> struct Glsl<ivec4> { static constexpr const char* name = "ivec4"; };
template <> struct Glsl<mat4> { static constexpr const char* name = "mat4"; };
template <> struct Glsl<ImpostorDraw> { static constexpr const char* name = "ImpostorDraw"; };

struct MemberDecl {
  std::string name;
  size_t offset;
  std::string glsl_type;  // element type for arrays
  size_t array_length;    // 0: not an array
  size_t element_size;    // sizeof the element (arrays: the stride GLSL must use)
  size_t matrix_stride;   // bytes per column, 0 for non-matrices
};

struct StructDecl {
  std::string name;
  size_t size;
  std::vector<MemberDecl> members;
};

template <class M>
MemberDecl member(const char* name, size_t offset) {
  using E = std::remove_all_extents_t<M>;
  size_t matrix_stride = 0;
  if constexpr (std::is_same_v<E, mat4>) matrix_stride = sizeof(mat4::col_type);
  return {name, offset, Glsl<E>::name, std::is_array_v<M> ? std::extent_v<M> : 0, sizeof(E), matrix_stride};
}

// M(x) inside GPU_STRUCT_DECL(S, ...) describes member S::x.
#define M(m) member<decltype(Self::m)>(#m, offsetof(Self, m))
#define GPU_STRUCT_DECL(S, ...)                     \
  [] {                                              \
    using Self = S;                                 \
    return StructDecl{#S, sizeof(S), {__VA_ARGS__}}; \
  }()

// Every struct of gpu_types.h the GPU reads or writes.
const std::vector<StructDecl>& shared_structs() {
  static const std::vector<StructDecl> structs = {
      GPU_STRUCT_DECL(FrameData, M(view_proj), M(inv_view_proj), M(camera_pos), M(sun_dir), M(sky_zenith),
                      M(sky_horizon), M(fog), M(frustum), M(lod), M(prune), M(lod_camera), M(prev_view_proj),
                      M(prev_inv_view_proj), M(prev_camera), M(pyramid), M(instance_count), M(leaf_command_base), M(prune_mode),
                      M(view_flags), M(occlusion), M(tail_capacity), M(tail_job_capacity), M(shadows),
                      M(shadow_view_proj), M(shadow_planes), M(shadow_splits), M(shadow_texel), M(camera_forward),
                      M(light), M(impostor), M(impostors), M(receiver_mask), M(frame_pad1), M(frame_pad2)),
      GPU_STRUCT_DECL(Instance, M(position_scale), M(yaw_cos_sin), M(model), M(tint)),
      GPU_STRUCT_DECL(Model, M(bounding_sphere), M(bark_color), M(leaf_color), M(card_corners), M(lod_first_index),
                      M(lod_index_count), M(lod_vertex_offset), M(lod_error), M(lod_count), M(leaf_texture_layer),
                      M(card_first_index), M(card_index_count), M(card_vertex_offset), M(leaf_offset),
                      M(leaf_count), M(table_offset), M(has_tables), M(sample_offset), M(sample_count),
                      M(occlusion_margin), M(card_radius), M(bark_texture_layer), M(crown_extinction), M(pr_size0),
                      M(leaf_quad_first_index), M(impostor_layer), M(impostor_cutoff), M(impostor_q)),
      GPU_STRUCT_DECL(HullSample, M(position), M(normal)),
      GPU_STRUCT_DECL(InstanceState, M(occlusion), M(visible), M(occluded), M(pad)),
      GPU_STRUCT_DECL(Leaf, M(position_scale), M(rotation), M(color), M(crown_depth)),
      GPU_STRUCT_DECL(TailJob, M(command), M(first_leaf), M(end_leaf), M(base)),
      GPU_STRUCT_DECL(DrawCommand, M(index_count), M(instance_count), M(first_index), M(vertex_offset),
                      M(first_instance), M(instance), M(lambda), M(area_scale), M(shown_lambda), M(leaf_list), M(fade)),
      GPU_STRUCT_DECL(ImpostorEntry, M(instance), M(fade)),
      GPU_STRUCT_DECL(ImpostorDraw, M(index_count), M(instance_count), M(first_index), M(vertex_offset), M(first_instance)),
      GPU_STRUCT_DECL(DrawCounts, M(branch_draws), M(leaf_draws), M(leaves_drawn), M(branch_triangles),
                      M(lod_draws), M(lambda_sum), M(occluded_instances), M(leaves_saved), M(triangles_saved),
                      M(tail_jobs), M(tail_groups_y), M(tail_groups_z), M(tail_leaves), M(shadow_branch_draws),
                      M(shadow_leaf_draws), M(shadow_triangles), M(shadow_leaves), M(impostor_draws)),
      GPU_STRUCT_DECL(PrCounts, M(tp), M(fp), M(fn), M(pad)),
      GPU_STRUCT_DECL(PrCountPush, M(pixel_count), M(reference_offset), M(branch_offset), M(result), M(width), M(lattices),
                      M(phase_result)),
      GPU_STRUCT_DECL(DepthPyramidPush, M(source_size), M(destination_size), M(first_level), M(pad)),
      GPU_STRUCT_DECL(PresentPush, M(offset), M(size)),
      GPU_STRUCT_DECL(DrawPush, M(command_base), M(cascade)),
  };
  return structs;
}
#undef M
#undef GPU_STRUCT_DECL

const StructDecl* find_struct(const std::string& name) {
  for (const StructDecl& s : shared_structs())
    if (s.name == name) return &s;
  return nullptr;
}

// The three pipeline layouts and the shaders that use each.
struct PushDecl {
  VkPushConstantRange range;
  const char* push_struct;
};
struct LayoutDecl {
  const char* name;
  std::vector<VkDescriptorSetLayoutBinding> bindings;
  std::vector<PushDecl> pushes;  // non-overlapping ranges, one struct each
};

// The renderer's set 0: the union of what its passes declare (as engine/render/renderer.cpp
// builds it with create_descriptor_table).
std::vector<VkDescriptorSetLayoutBinding> renderer_set() {
  std::vector<VkDescriptorSetLayoutBinding> set;
  for (const Binding& b : merge_bindings(kRendererBindingLists)) set.push_back({b.binding, b.type, 1, b.stages, nullptr});
  return set;
}

const std::vector<LayoutDecl>& layouts() {
  static const std::vector<LayoutDecl> all = {
      {"renderer", renderer_set(), {{kPrCountPushRange, "PrCountPush"}, {kDrawPushRange, "DrawPush"}}},
      {"depth pyramid", {std::begin(kPyramidSetBindings), std::end(kPyramidSetBindings)},
       {{kPyramidPushRange, "DepthPyramidPush"}}},
      {"present", {std::begin(kPresentSetBindings), std::end(kPresentSetBindings)}, {{kPresentPushRange, "PresentPush"}}},
  };
  return all;
}
const LayoutDecl& layout_of(const std::string& shader) {
  if (shader.rfind("depth_pyramid_", 0) == 0) return layouts()[1];
  if (shader.rfind("present_", 0) == 0) return layouts()[2];
  return layouts()[0];
}

struct SpecDecl {
  const char* shader;
  const char* name;  // the GLSL constant
  uint32_t id;
};
const SpecDecl kSpecConstants[] = {
    {"tree_frag", "LEAF", SPEC_LEAF}, {"tree_frag", "COVERAGE_LATTICES", SPEC_COVERAGE_LATTICES},
    {"leaf_msaa_frag", "LEAF", SPEC_LEAF}, {"leaf_msaa_frag", "COVERAGE_LATTICES", SPEC_COVERAGE_LATTICES},
    {"leaf_msaa_frag", "COVERAGE_SAMPLES", SPEC_COVERAGE_SAMPLES}, {"depth_pyramid_comp", "MINMAX_SAMPLER", SPEC_MINMAX_SAMPLER},
    {"tree_frag", "LEAF_SHADOW_PER_FRAGMENT", SPEC_LEAF_SHADOW_PER_FRAGMENT}, {"leaf_msaa_frag", "LEAF_SHADOW_PER_FRAGMENT", SPEC_LEAF_SHADOW_PER_FRAGMENT},
    {"tree_frag", "VIEWS", SPEC_VIEWS}, {"leaf_msaa_frag", "VIEWS", SPEC_VIEWS}};

struct AttrDecl {
  const char* name;  // the GLSL vertex input
  uint32_t location;
  const char* glsl_type;
  VkFormat format;   // what that type reads
};
const AttrDecl kAttributes[] = {
    {"in_position", ATTR_POSITION, "vec3", VK_FORMAT_R32G32B32_SFLOAT},
    {"in_normal", ATTR_NORMAL, "vec3", VK_FORMAT_R32G32B32_SFLOAT},
    {"in_uv", ATTR_UV, "vec2", VK_FORMAT_R32G32_SFLOAT},
};

// ---- the GLSL side: spirv-cross --reflect of every compiled shader ----------------------

struct Shader {
  std::string name;  // registry name, e.g. "cull_comp"
  json reflection;
  VkShaderStageFlagBits stage;
};

std::string run(const std::string& command, int* status) {
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) {
    *status = -1;
    return out;
  }
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof(buf), pipe)) > 0) out.append(buf, n);
  *status = pclose(pipe);
  return out;
}

const std::vector<Shader>& shaders() {
  static const std::vector<Shader> all = [] {
    std::vector<Shader> v;
    const fs::path dir = FOREST_SHADER_DIR;
    if (!fs::is_regular_file(FOREST_SPIRV_CROSS)) {
      ADD_FAILURE() << "spirv-cross not found (" << FOREST_SPIRV_CROSS
                    << "): install Debian's spirv-cross (scripts/install-deps.sh) and reconfigure";
      return v;
    }
    std::vector<fs::path> files;
    for (const fs::directory_entry& e : fs::directory_iterator(dir))
      if (e.path().extension() == ".spv") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    for (const fs::path& f : files) {
      int status = 0;
      std::string out = run(std::string("'") + FOREST_SPIRV_CROSS + "' '" + f.string() + "' --reflect 2>&1", &status);
      if (status != 0) {
        ADD_FAILURE() << "spirv-cross --reflect " << f << " failed (" << status << "): " << out;
        continue;
      }
      Shader s{f.stem().string(), json::parse(out, nullptr, false), VK_SHADER_STAGE_ALL};
      if (s.reflection.is_discarded()) {
        ADD_FAILURE() << "spirv-cross --reflect " << f << ": not JSON: " << out.substr(0, 400);
        continue;
      }
      std::string mode = s.reflection["entryPoints"][0].value("mode", "");
      s.stage = mode == "vert"   ? VK_SHADER_STAGE_VERTEX_BIT
                : mode == "frag" ? VK_SHADER_STAGE_FRAGMENT_BIT : mode == "geom" ? VK_SHADER_STAGE_GEOMETRY_BIT
                : mode == "comp" ? VK_SHADER_STAGE_COMPUTE_BIT : VK_SHADER_STAGE_ALL;
      if (s.stage == VK_SHADER_STAGE_ALL) ADD_FAILURE() << s.name << ": unknown shader stage '" << mode << "'";
      v.push_back(std::move(s));
    }
    return v;
  }();
  return all;
}

const json& types_of(const Shader& s) {
  static const json empty = json::object();
  return s.reflection.contains("types") ? s.reflection["types"] : empty;
}

// A member's type as GLSL spells it: basic types as is, structs by name.
std::string type_name(const json& types, const std::string& type) {
  if (!type.empty() && type[0] == '_' && types.contains(type)) return types[type].value("name", type);
  return type;
}

bool has_explicit_layout(const json& type) {
  for (const json& m : type["members"])
    if (m.contains("offset")) return true;
  return false;
}

size_t extent(const json& types, const json& type);

// Bytes a member occupies (from the compiler's strides; basic types 4 bytes per component).
size_t member_size(const json& types, const json& m) {
  if (m.contains("array")) {
    size_t count = 1;
    for (const json& d : m["array"]) count *= d.get<size_t>();
    return m.value("array_stride", size_t(0)) * count;
  }
  std::string t = m["type"];
  if (!t.empty() && t[0] == '_') return extent(types, types[t]);
  auto components = [](const std::string& s, size_t at) { return at < s.size() ? size_t(s[at] - '0') : 1; };
  if (t.rfind("mat", 0) == 0) return m.value("matrix_stride", size_t(16)) * components(t, 3);
  if (t == "float" || t == "int" || t == "uint" || t == "bool") return 4;
  if (t.rfind("vec", 0) == 0) return 4 * components(t, 3);
  if (t.rfind("ivec", 0) == 0 || t.rfind("uvec", 0) == 0 || t.rfind("bvec", 0) == 0) return 4 * components(t, 4);
  ADD_FAILURE() << "member " << m.value("name", "?") << ": size of GLSL type " << t << " unknown to the test";
  return 0;
}

// End of the last member (what a push-constant range must cover).
size_t extent(const json& types, const json& type) {
  size_t end = 0;
  for (const json& m : type["members"]) end = std::max(end, m.value("offset", size_t(0)) + member_size(types, m));
  return end;
}

std::set<std::string> block_types(const Shader& s) {
  std::set<std::string> blocks;
  for (const char* kind : {"ubos", "ssbos", "push_constants"})
    if (s.reflection.contains(kind))
      for (const json& r : s.reflection[kind]) blocks.insert(r["type"].get<std::string>());
  return blocks;
}

const char* descriptor_type_name(VkDescriptorType t) {
  switch (t) {
    case VK_DESCRIPTOR_TYPE_SAMPLER: return "SAMPLER";
    case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER: return "COMBINED_IMAGE_SAMPLER";
    case VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE: return "SAMPLED_IMAGE";
    case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE: return "STORAGE_IMAGE";
    case VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER: return "UNIFORM_TEXEL_BUFFER";
    case VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER: return "STORAGE_TEXEL_BUFFER";
    case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER: return "UNIFORM_BUFFER";
    case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER: return "STORAGE_BUFFER";
    case VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT: return "INPUT_ATTACHMENT";
    default: return "other";
  }
}

TEST(GpuInterface, ShadersWereCompiledAndReflected) {
  std::set<std::string> names;
  for (const Shader& s : shaders()) names.insert(s.name);
  // The pipelines of the renderer, depth pyramid and present pass.
  for (const char* expected : {"cull_comp", "tail_cull_comp", "pr_count_comp", "depth_pyramid_comp", "sky_vert",
                               "sky_frag", "terrain_vert", "terrain_frag", "branch_vert", "leaf_vert", "leaf_pulled_vert",
                               "leaf_card_geom", "leaf_caster_vert", "leaf_caster_pulled_vert", "tree_frag",
                               "pyramid_overlay_vert", "pyramid_overlay_frag", "present_vert", "present_frag"})
    EXPECT_TRUE(names.count(expected)) << expected << ".spv missing from " << FOREST_SHADER_DIR;
  // Every kind of resource the reflection lists is one the tests below check.
  const std::set<std::string> known = {"entryPoints", "types",           "inputs",           "outputs",
                                       "textures",    "images",          "ssbos",            "ubos",
                                       "push_constants", "separate_images", "separate_samplers", "subpass_inputs",
                                       "specialization_constants"};
  for (const Shader& s : shaders())
    for (auto& [key, value] : s.reflection.items())
      EXPECT_TRUE(known.count(key)) << s.name << ": reflection lists '" << key << "', which this test does not check";
}

// Offsets, types and sizes of every shared struct in every shader that declares it.
TEST(GpuInterface, StructLayoutsMatchTheShaders) {
  ASSERT_FALSE(shaders().empty());
  std::map<std::string, int> seen, sizes_checked;
  for (const Shader& s : shaders()) {
    const json& types = types_of(s);
    const std::set<std::string> blocks = block_types(s);
    for (auto& [id, type] : types.items()) {
      const std::string name = type.value("name", "");
      if (blocks.count(id) || !has_explicit_layout(type)) continue;  // blocks: by binding below; locals: no layout
      const StructDecl* decl = find_struct(name);
      if (!decl) {
        ADD_FAILURE() << s.name << ": struct " << name << " is laid out in a buffer but is not a shared struct of "
                      << "gpu_types.h listed in tests/unit/test_gpu_interface.cpp";
        continue;
      }
      ++seen[name];
      std::set<std::string> glsl_members;
      for (const json& m : type["members"]) {
        const std::string member = m.value("name", "");
        glsl_members.insert(member);
        const MemberDecl* cpp = nullptr;
        for (const MemberDecl& d : decl->members)
          if (d.name == member) cpp = &d;
        if (!cpp) {
          ADD_FAILURE() << s.name << ": struct " << name << " member '" << member << "' (GLSL offset "
                        << m.value("offset", size_t(0)) << ") has no C++ counterpart";
          continue;
        }
        const size_t offset = m.value("offset", size_t(0));
        EXPECT_EQ(offset, cpp->offset) << s.name << ": struct " << name << " member '" << member << "': GLSL offset "
                                       << offset << ", C++ offsetof " << cpp->offset;
        const std::string glsl_type = type_name(types, m["type"]);
        EXPECT_EQ(glsl_type, cpp->glsl_type) << s.name << ": struct " << name << " member '" << member
                                             << "': GLSL type " << glsl_type << ", C++ type " << cpp->glsl_type;
        const size_t length = m.contains("array") ? m["array"][0].get<size_t>() : 0;
        EXPECT_EQ(length, cpp->array_length) << s.name << ": struct " << name << " member '" << member
                                             << "': GLSL array length " << length << ", C++ " << cpp->array_length;
        if (m.contains("array_stride")) {
          EXPECT_EQ(m["array_stride"].get<size_t>(), cpp->element_size)
              << s.name << ": struct " << name << " member '" << member << "': GLSL array stride "
              << m["array_stride"] << ", C++ element size " << cpp->element_size;
        }
        if (m.contains("matrix_stride")) {
          EXPECT_EQ(m["matrix_stride"].get<size_t>(), cpp->matrix_stride)
              << s.name << ": struct " << name << " member '" << member << "': GLSL matrix stride "
              << m["matrix_stride"] << ", C++ column size " << cpp->matrix_stride;
        }
      }
      for (const MemberDecl& d : decl->members)
        EXPECT_TRUE(glsl_members.count(d.name)) << s.name << ": struct " << name << " has no member '" << d.name
                                                << "' (C++ offsetof " << d.offset << ")";
    }

    // Sizes: where a shared struct is an array element (stride) or a block's last member
    // (block size; push constants: the end of the last member).
    std::map<std::string, size_t> block_size;
    for (const char* kind : {"ubos", "ssbos"})
      if (s.reflection.contains(kind))
        for (const json& r : s.reflection[kind]) block_size[r["type"]] = r.value("block_size", size_t(0));
    for (auto& [id, type] : types.items()) {
      if (!has_explicit_layout(type)) continue;
      const json& members = type["members"];
      for (size_t i = 0; i < members.size(); ++i) {
        const json& m = members[i];
        const StructDecl* decl = find_struct(type_name(types, m["type"]));
        if (!decl) continue;
        const std::string where = s.name + ": " + type.value("name", "") + "." + m.value("name", "");
        if (m.contains("array_stride")) {
          EXPECT_EQ(m["array_stride"].get<size_t>(), decl->size)
              << where << ": array stride of struct " << decl->name << " " << m["array_stride"] << ", C++ sizeof "
              << decl->size;
          ++sizes_checked[decl->name];
        } else if (i + 1 == members.size() && block_size.count(id)) {
          const size_t size = block_size[id] - m.value("offset", size_t(0));
          EXPECT_EQ(size, decl->size) << where << ": struct " << decl->name << " occupies " << size
                                      << " bytes of its block, C++ sizeof " << decl->size;
          ++sizes_checked[decl->name];
        } else if (i + 1 == members.size() && blocks.count(id)) {  // push constants
          const size_t size = extent(types, types[m["type"].get<std::string>()]);
          EXPECT_EQ(size, decl->size) << where << ": push-constant struct " << decl->name << " ends at byte "
                                      << size << ", C++ sizeof " << decl->size;
          ++sizes_checked[decl->name];
        }
      }
    }
  }
  for (const StructDecl& d : shared_structs()) {
    EXPECT_GT(seen[d.name], 0) << "struct " << d.name << " of gpu_types.h is used by no compiled shader";
    EXPECT_GT(sizes_checked[d.name], 0) << "struct " << d.name
                                        << ": no shader uses it as an array element or a block's last member, "
                                        << "so its size was never checked against sizeof";
  }
}

// Bindings, descriptor types and stages against the set layouts the C++ side declares (the renderer passes, depth pyramid, present).
TEST(GpuInterface, BindingsMatchTheSetLayouts) {
  ASSERT_FALSE(shaders().empty());
  std::map<std::pair<const LayoutDecl*, uint32_t>, int> used;
  for (const Shader& s : shaders()) {
    const LayoutDecl& layout = layout_of(s.name);
    struct Kind {
      const char* key;
      VkDescriptorType type;
    };
    for (Kind kind : {Kind{"ubos", VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER}, Kind{"ssbos", VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                      Kind{"textures", VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                      Kind{"images", VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
                      Kind{"separate_images", VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE},
                      Kind{"separate_samplers", VK_DESCRIPTOR_TYPE_SAMPLER},
                      Kind{"subpass_inputs", VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT}}) {
      if (!s.reflection.contains(kind.key)) continue;
      for (const json& r : s.reflection[kind.key]) {
        VkDescriptorType type = kind.type;
        const std::string glsl_type = r.value("type", "");
        if (glsl_type.find("Buffer") != std::string::npos)  // samplerBuffer, imageBuffer
          type = type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE ? VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER
                                                          : VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
        const uint32_t set = r.value("set", 0u), binding = r.value("binding", 0u);
        const std::string what = s.name + ": " + r.value("name", "?") + " (set " + std::to_string(set) +
                                 ", binding " + std::to_string(binding) + ", " + descriptor_type_name(type) + ")";
        EXPECT_EQ(set, 0u) << what << ": the " << layout.name << " pipeline layout has only set 0";
        const VkDescriptorSetLayoutBinding* decl = nullptr;
        for (const VkDescriptorSetLayoutBinding& b : layout.bindings)
          if (b.binding == binding) decl = &b;
        if (!decl) {
          ADD_FAILURE() << what << ": the C++ " << layout.name << " set declares no binding " << binding;
          continue;
        }
        ++used[{&layout, binding}];
        EXPECT_EQ(type, decl->descriptorType) << what << ": the C++ " << layout.name << " set declares binding "
                                              << binding << " as " << descriptor_type_name(decl->descriptorType);
        const uint32_t count = r.contains("array") ? r["array"][0].get<uint32_t>() : 1u;
        EXPECT_EQ(count, decl->descriptorCount) << what << ": descriptor count";
        EXPECT_TRUE(decl->stageFlags & s.stage) << what << ": the C++ " << layout.name << " set's binding "
                                                << binding << " is not visible to this stage";
      }
    }
  }
  for (const LayoutDecl& layout : layouts())
    for (const VkDescriptorSetLayoutBinding& b : layout.bindings)
      EXPECT_GT((used[{&layout, b.binding}]), 0) << "the C++ " << layout.name << " set's binding " << b.binding
                                               << " is used by no compiled shader";
}

TEST(GpuInterface, PushConstantsMatchThePipelineLayouts) {
  ASSERT_FALSE(shaders().empty());
  std::map<const PushDecl*, int> pushed;
  for (const Shader& s : shaders()) {
    if (!s.reflection.contains("push_constants")) continue;
    const LayoutDecl& layout = layout_of(s.name);
    const json& types = types_of(s);
    for (const json& r : s.reflection["push_constants"]) {
      const json& block = types[r["type"].get<std::string>()];
      const size_t size = extent(types, block);
      // The block wraps the one struct of gpu_types.h the C++ side pushes to this stage.
      ASSERT_EQ(block["members"].size(), 1u) << s.name << ": push-constant block " << block.value("name", "")
                                             << " must hold one struct of gpu_types.h";
      const PushDecl* push = nullptr;
      for (const PushDecl& p : layout.pushes)
        if (p.range.stageFlags & s.stage) push = &p;
      ASSERT_NE(push, nullptr) << s.name << ": no push-constant range of the C++ " << layout.name
                               << " layout is visible to this stage";
      const std::string wrapped = type_name(types, block["members"][0]["type"]);
      EXPECT_EQ(wrapped, push->push_struct) << s.name << ": push-constant block " << block.value("name", "")
                                            << " holds " << wrapped << ", the C++ " << layout.name
                                            << " layout pushes " << push->push_struct;
      const StructDecl* decl = find_struct(push->push_struct);
      ASSERT_NE(decl, nullptr);
      EXPECT_EQ(size_t(push->range.size), decl->size) << layout.name << ": push range size vs sizeof "
                                                      << push->push_struct;
      const size_t offset = block["members"][0].value("offset", 0);
      EXPECT_EQ(offset, size_t(push->range.offset)) << s.name << ": push-constant block starts at byte " << offset
                                                    << ", the C++ range at " << push->range.offset;
      EXPECT_EQ(size, push->range.offset + decl->size)
          << s.name << ": push-constant block ends at byte " << size << ", the C++ range at "
          << push->range.offset + decl->size;
      ++pushed[push];
    }
  }
  for (const LayoutDecl& layout : layouts())
    for (const PushDecl& p : layout.pushes) {
      EXPECT_GT(pushed[&p], 0) << "the C++ " << layout.name << " layout's push constants (" << p.push_struct
                               << ") are read by no compiled shader";
      for (const PushDecl& q : layout.pushes)
        if (&p != &q)
          EXPECT_TRUE(p.range.offset + p.range.size <= q.range.offset || q.range.offset + q.range.size <= p.range.offset)
              << layout.name << ": push ranges " << p.push_struct << " and " << q.push_struct << " overlap";
    }
}

TEST(GpuInterface, SpecializationConstantIdsMatchSpecMacros) {
  ASSERT_FALSE(shaders().empty());
  std::map<std::string, int> seen;
  for (const Shader& s : shaders()) {
    if (!s.reflection.contains("specialization_constants")) continue;
    for (const json& c : s.reflection["specialization_constants"]) {
      const std::string name = c.value("name", "");
      const uint32_t id = c.value("id", ~0u);
      const SpecDecl* decl = nullptr;
      for (const SpecDecl& d : kSpecConstants)
        if (s.name == d.shader && name == d.name) decl = &d;
      if (!decl) {
        ADD_FAILURE() << s.name << ": specialization constant " << name << " (constant_id " << id
                      << ") has no SPEC_* declaration in gpu_types.h listed in tests/unit/test_gpu_interface.cpp";
        continue;
      }
      ++seen[std::string(decl->shader) + "." + decl->name];
      EXPECT_EQ(id, decl->id) << s.name << ": specialization constant " << name << " has constant_id " << id
                              << ", its SPEC_* macro is " << decl->id;
      const std::string type = c.value("type", "");
      EXPECT_TRUE(type == "bool" || type == "uint" || type == "int" || type == "float")
          << s.name << ": specialization constant " << name << " is " << type
          << "; the C++ side passes 32-bit values (vk::SpecConstant)";
    }
  }
  for (const SpecDecl& d : kSpecConstants)
    EXPECT_GT(seen[std::string(d.shader) + "." + d.name], 0)
        << "specialization constant " << d.name << " (id " << d.id << ") not found in " << d.shader;
}

TEST(GpuInterface, VertexInputsMatchAttributeLocations) {
  ASSERT_FALSE(shaders().empty());
  const std::span<const VkVertexInputAttributeDescription> attributes = vk::vertex_attributes();
  EXPECT_EQ(attributes.size(), std::size(kAttributes));
  for (const AttrDecl& a : kAttributes) {
    const VkVertexInputAttributeDescription* desc = nullptr;
    for (const VkVertexInputAttributeDescription& d : attributes)
      if (d.location == a.location) desc = &d;
    ASSERT_NE(desc, nullptr) << "vk::vertex_attributes() has no location " << a.location << " (" << a.name << ")";
    EXPECT_EQ(desc->format, a.format) << a.name << ": vk::vertex_attributes() format of location " << a.location;
  }
  std::map<std::string, int> seen;
  for (const Shader& s : shaders()) {
    if (s.stage != VK_SHADER_STAGE_VERTEX_BIT || !s.reflection.contains("inputs")) continue;
    for (const json& in : s.reflection["inputs"]) {
      const std::string name = in.value("name", "");
      const uint32_t location = in.value("location", ~0u);
      const AttrDecl* decl = nullptr;
      for (const AttrDecl& a : kAttributes)
        if (name == a.name) decl = &a;
      if (!decl) {
        ADD_FAILURE() << s.name << ": vertex input " << name << " (location " << location
                      << ") is no ATTR_* attribute of forest::Vertex";
        continue;
      }
      ++seen[name];
      EXPECT_EQ(location, decl->location) << s.name << ": vertex input " << name << " at location " << location
                                          << ", its ATTR_* macro is " << decl->location;
      EXPECT_EQ(in.value("type", ""), decl->glsl_type) << s.name << ": vertex input " << name << " type";
    }
  }
  for (const AttrDecl& a : kAttributes)
    EXPECT_GT(seen[a.name], 0) << "vertex attribute " << a.name << " is read by no compiled vertex shader";
}

}  // namespace
