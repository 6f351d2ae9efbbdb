// Every struct the GPU reads or writes, declared once for C++ and GLSL.
// std430 layout rules: vec4-aligned members first, scalars packed after; no vec3.
#ifndef FOREST_GPU_TYPES_H
#define FOREST_GPU_TYPES_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace forest::gpu {
using uint = uint32_t;
using vec2 = glm::vec2;
using vec4 = glm::vec4;
using mat4 = glm::mat4;
#define GPU_STRUCT struct alignas(16)
#else
#define GPU_STRUCT struct
#endif

// Descriptor bindings of the single set every pipeline shares (set 0).
#define BINDING_FRAME 0
#define BINDING_INSTANCES 1
#define BINDING_MODELS 2
#define BINDING_LEAVES 3
#define BINDING_COMMANDS 4
#define BINDING_DRAW_COUNTS 5

#define CULL_GROUP_SIZE 64

// Per-frame constants (uniform buffer).
GPU_STRUCT FrameData {
  mat4 view_proj;
  mat4 inv_view_proj;
  vec4 camera_pos;      // xyz, w = unused
  vec4 sun_dir;         // xyz toward the sun (normalized), w = sun intensity
  vec4 sky_zenith;      // rgb linear
  vec4 sky_horizon;     // rgb linear
  vec4 fog;             // rgb linear, w = density per meter
  vec4 frustum[6];      // planes, xyz = inward normal, w = distance; dot(n,p)+w >= 0 inside
  uint instance_count;
  uint leaf_command_base;  // index of the first leaf command in the command buffer
  uint pad0;
  uint pad1;
};

// One tree instance in the scene: placed once at load, never touched per frame by the CPU.
GPU_STRUCT Instance {
  vec4 position_scale;  // xyz world position of the tree base, w = uniform scale
  vec2 yaw_cos_sin;     // rotation about +Y
  uint model;           // index into models[]
  uint tint;            // packed rgba8 per-instance color variation
};

// One tree model (asset); its leaves are contiguous in leaves[] in priority order.
GPU_STRUCT Model {
  vec4 bounding_sphere;      // model space, xyz center, w radius
  vec4 bark_color;           // linear rgb
  vec4 leaf_color;           // linear rgb
  uint branch_first_index;
  uint branch_index_count;
  int branch_vertex_offset;
  uint card_first_index;     // the one leaf card mesh of this model
  uint card_index_count;
  int card_vertex_offset;
  uint leaf_offset;          // first leaf of this model in leaves[]
  uint leaf_count;
};

// One leaf: an instance of the model's leaf card (glTF EXT_mesh_gpu_instancing TRS).
GPU_STRUCT Leaf {
  vec4 position_scale;  // model space position, w = uniform scale
  vec4 rotation;        // unit quaternion xyzw
};

// VkDrawIndexedIndirectCommand followed by the tree instance the draw belongs to.
struct DrawCommand {
  uint index_count;
  uint instance_count;
  uint first_index;
  int vertex_offset;
  uint first_instance;
  uint instance;
};

// Counters written by cull.comp, read by vkCmdDrawIndexedIndirectCount.
struct DrawCounts {
  uint branch_draws;
  uint leaf_draws;
  uint leaves_drawn;
  uint pad;
};

#ifdef __cplusplus
}  // namespace forest::gpu
#undef GPU_STRUCT
#endif
#endif
