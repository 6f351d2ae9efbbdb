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
using ivec2 = glm::ivec2;
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using ivec4 = glm::ivec4;
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
#define BINDING_LEAF_TEXTURES 6
#define BINDING_PRUNE_TABLES 7
#define BINDING_COVERAGE_REFERENCE 8
#define BINDING_COVERAGE_TEST 9
#define BINDING_PR_COUNTS 10
#define BINDING_DEPTH_PYRAMID 11   // previous frame's depth pyramid (farthest depth per texel)
#define BINDING_HULL_SAMPLES 12    // HullSample per model point (occlusion test, Neubert 2012 §7.4)
#define BINDING_INSTANCE_STATE 13  // InstanceState: occlusion feedback kept across frames
#define BINDING_TAIL_JOBS 14       // TailJob per partly occluded tree (cull.comp -> tail_cull.comp)
#define BINDING_TAIL_LEAVES 15     // leaf indices of the visible tails, in priority order
#define BINDING_BARK_ALBEDO 16     // sampler2DArray: bark colour, one layer per bark (Model.bark_texture_layer)
#define BINDING_BARK_NORMALS 17    // sampler2DArray: bark tangent-space normal maps, the same layers
#define BINDING_SHADOW_MAP 18      // sampler2DArrayShadow: the sun's cascaded shadow map, one layer per cascade
#define BINDING_IMPOSTOR_LIST 19    // ImpostorEntry per far tree drawn as an impostor (cull.comp -> impostor.vert)
#define BINDING_IMPOSTOR_ALBEDO 20  // sampler2DArray: impostor atlases, albedo (sRGB) and coverage, one layer per model
#define BINDING_IMPOSTOR_NORMALS 21 // sampler2DArray: the same atlases' normal (octahedral xy) and height
#define BINDING_RECEIVER_MASK 22    // uint: per cascade and light-space cell, the deepest visible receiver

// Descriptor bindings of depth_pyramid.comp's set (one set per pyramid level).
#define PYRAMID_BINDING_SOURCE 0       // sampler2D: the depth buffer (level 0) or the level above
#define PYRAMID_BINDING_DESTINATION 1  // r32f image2D: the level written

// Descriptor bindings of present.frag's set (forest walk's copy pass).
#define PRESENT_BINDING_RENDERED 0  // sampler2D: the renderer's finished frame

// Specialization-constant ids: layout(constant_id = SPEC_*) in GLSL, VkSpecializationMapEntry
// ids in C++. Each shader has its own id space; every constant is 32 bits (a bool unless named).
#define SPEC_LEAF 0               // tree.frag: drawing leaf cards (texture alpha, translucency)
#define SPEC_COVERAGE_SAMPLES 1   // leaf_msaa.frag (uint): the pipeline's samples, which the leaf alpha covers
#define SPEC_COVERAGE_LATTICES 2  // tree.frag: bake coverage at every PR size in one render (PR_SIZES)
#define SPEC_LEAF_SHADOW_PER_FRAGMENT 3  // tree.frag: leaves read the shadow map per fragment, not once a leaf (lighting.glsl)
#define SPEC_VIEWS 4              // tree.frag: honours view_flags' mask, λ, shadow and impostor bake views (false: shaded only)
#define SPEC_MINMAX_SAMPLER 0     // depth_pyramid.comp: levels >= 1 reduce with a MIN sampler

// Vertex attribute locations of forest::Vertex (binding 0), in every vertex shader with inputs.
#define ATTR_POSITION 0  // vec3
#define ATTR_NORMAL 1    // vec3
#define ATTR_UV 2        // vec2

// FrameData.prune_mode: how many leaves of each tree are drawn (Neubert 2012 ch7).
#define PRUNE_FULL 0   // every leaf, λ = 1
#define PRUNE_COOK 1   // λ = (1 − d)², area scale s = 1/λ (Cook et al. 2007 as in ch7)
#define PRUNE_OPT 2    // λ_opt(d) and s_opt(λ) from the model's baked PR tables
#define PRUNE_FIXED 3  // one λ and s for every tree (bake measurements, tests)
#define PRUNE_TARGET 4 // smallest λ whose baked Q at the tree's projected size reaches prune.z

// FrameData.view_flags
#define VIEW_LAMBDA 1  // color trees by their detail level λ (Fig 7.15)
#define VIEW_MASK 2    // write coverage only (white): PR measurement
#define VIEW_SHADOW 4  // grey = the sun's shadow-map visibility (tests, debugging)
#define VIEW_LEAF_INSTANCED 8  // leaf draws as instances of the card (else pulled: leaf_draw.glsl)
#define VIEW_IMPOSTOR_ALBEDO 16  // impostor bake: unlit albedo (times the sky visibility), no background
#define VIEW_IMPOSTOR_NORMAL 32  // impostor bake: model-space normal (octahedral) and height (FrameData.impostor)

// FrameData.impostors: far trees as one textured quad (impostor_pass.h, Model.impostor_q).
#define IMPOSTORS_OFF 0
#define IMPOSTORS_SWITCHED 1  // where the baked Q of the impostor reaches the mesh's at the tree's λ and size
#define IMPOSTORS_ALWAYS 2    // every tree with an impostor (bake measurements, tests)
// Hemi-octahedral impostor atlas (impostor_math.h): IMPOSTOR_GRID² views of the upper
// hemisphere, each IMPOSTOR_VIEW_SIZE pixels square, in one atlas layer per model.
#define IMPOSTOR_GRID 12
#define IMPOSTOR_VIEW_SIZE 64
#define IMPOSTOR_ATLAS_SIZE (IMPOSTOR_GRID * IMPOSTOR_VIEW_SIZE)
// Q difference over which mesh and impostor cross-fade (dithered): the impostor alone once its
// Q passes the mesh's by this much, the mesh alone while it does not pass it at all.
#define IMPOSTOR_FADE_BAND 0.02
// Draw-list slots of impostors: the camera's, then one per cascade, each instance_count long.
#define IMPOSTOR_LISTS (1 + SHADOW_CASCADES)

// The shared index pattern at Model.leaf_quad_first_index: one quad, LEAF_QUAD_INDICES (corners
// 0 1 2, 0 2 3; impostors draw it), then the pulled leaves (leaf_draw.glsl): leaf j is the
// point j, LEAF_POINT_INDICES, that leaf_card.geom makes the triangle around its card
// (Model.card_corners); one draw per tree, no instancing.
#define LEAF_QUAD_INDICES 6
#define LEAF_POINT_INDICES 1

// Cascaded shadow maps of the sun (shadow_pass.h): cascades over [near, shadow_distance].
#define SHADOW_CASCADES 3
#define SHADOW_NONE 0xffffffffu  // DrawPush.cascade of the camera's own draws
#define SHADOW_PCF_TEXELS 3      // the filter's footprint: 3x3 bilinear compare taps (lighting.glsl)
// Receiver mask (receiver_mask.comp): per cascade a RECEIVER_MASK_CELLS² grid over the
// cascade's map; each cell holds the largest light-space depth (floatBitsToUint, 0: none) of
// the surfaces the previous frame saw there that the cascade shades, then one word with the
// largest of the whole cascade.
#define RECEIVER_MASK_CELLS 64
#define RECEIVER_MASK_WORDS (RECEIVER_MASK_CELLS * RECEIVER_MASK_CELLS + 1)  // per cascade
// The command buffer holds, for n instances: the camera's n branch draws, its 2n leaf draws
// (prefix and occlusion tail), then per cascade n branch draws followed by n leaf draws.
#define COMMANDS_PER_INSTANCE (3 + 2 * SHADOW_CASCADES)

// Target mode (PRUNE_TARGET): each tree draws the smallest λ whose q_opt reaches the quality
// and whose q_low, the 10th percentile of Q over the bake's views and sub-pixel phases (what
// single trees in a frame see), reaches the quality minus this.
#define TARGET_LOW_MARGIN 0.03
#define TARGET_LOW_QUANTILE 0.1  // the quantile q_low holds

// Per-model PR tables (floats in the prune table buffer, at Model.table_offset), measured at
// PR_SIZES projected sizes p_b = Model.pr_size0 / 2^b (pixels across the bounding sphere):
// per size b one block of TABLE_BLOCK floats, s_opt and q_opt at λ = i / (S_SAMPLES − 1),
// then λ_opt at the D_SAMPLES distances of d_sample(), then s_opt and q_opt at the F_SAMPLES
// far λ below the first, λ_f = 1 / ((S_SAMPLES − 1) · 2^(f+1)) (prune::far_lambda): where Cook's
// λ is that small (d ≥ 0.78) the leaf area to draw depends on the model and is measured too.
// Last q_low at the S_SAMPLES λ and at the F_SAMPLES far ones (TARGET_LOW_MARGIN).
#define S_SAMPLES 21
#define D_SAMPLES 20
#define F_SAMPLES 3
#define PR_SIZES 6
#define TABLE_BLOCK (3 * S_SAMPLES + D_SAMPLES + 3 * F_SAMPLES)
#define TABLE_Q_OPT S_SAMPLES             // offset of q_opt in a block
#define TABLE_LAMBDA_OPT (2 * S_SAMPLES)  // offset of λ_opt in a block
#define TABLE_S_FAR (2 * S_SAMPLES + D_SAMPLES)  // offset of the far s_opt in a block
#define TABLE_Q_FAR (TABLE_S_FAR + F_SAMPLES)    // offset of the far q_opt in a block
#define TABLE_Q_LOW (TABLE_Q_FAR + F_SAMPLES)    // offset of q_low in a block
#define TABLE_Q_LOW_FAR (TABLE_Q_LOW + S_SAMPLES)  // offset of the far q_low in a block
#define TABLE_FLOATS (PR_SIZES * TABLE_BLOCK)
// Bake coverage renders (SPEC_COVERAGE_LATTICES): size 0 in the red channel, and size b >= 1,
// 2^b times smaller, with the leaf texture read b mip levels coarser, in the channel
// prune::lattice_size assigns at that pixel's parity (size 5 at every pixel, sizes 1–4 at half
// of them). Each pixel of the render is the sample point of a render 2^b times smaller at one
// of its 4^b sub-pixel phases, so a size's count is summed over (half of or all) its phases:
// what trees at random sub-pixel positions see on average, not one phase's luck (one phase of
// 8 × 8 pixels is a few dozen pixels).
#if PR_SIZES != 6
#error "prune::lattice_size is written for six PR sizes"
#endif

#define MAX_BRANCH_LODS 8      // LOD0 + up to 7 coarser levels per model (structural_lod.h)
#define LEAF_TEXTURE_SIZE 256  // every model's leaf texture is one layer of a 2D array
#define BARK_TEXTURE_SIZE 256  // every bark's albedo and normal map are one layer of two 2D arrays

// FrameData.occlusion: depth-buffer occlusion feedback (Neubert 2012 §7.4).
#define OCCLUSION_ON 1   // test hull samples against the previous frame's pyramid
#define OCCLUSION_CUT 2  // no usable previous frame (first frame, camera cut): all count as visible

#define CULL_GROUP_SIZE 64
#define TAIL_GROUP_SIZE 64    // leaves tested at once by one tail_cull.comp workgroup
#define PYRAMID_GROUP_SIZE 8  // 8x8 texels per depth_pyramid.comp workgroup
#define PR_GROUP_SIZE 64
#define PR_PIXELS_PER_INVOCATION 32  // pr_count.comp

// Per-frame constants (uniform buffer).
GPU_STRUCT FrameData {
  mat4 view_proj;
  mat4 inv_view_proj;
  vec4 camera_pos;      // xyz, w = 0, or 1 + the one instance drawn (FrameSettings::solo_instance)
  vec4 sun_dir;         // xyz toward the sun (normalized), w = sun intensity
  vec4 sky_zenith;      // rgb linear
  vec4 sky_horizon;     // rgb linear
  vec4 fog;             // rgb linear, w = density per meter
  vec4 frustum[6];      // planes, xyz = inward normal, w = distance; dot(n,p)+w >= 0 inside
  vec4 lod;             // x = pixels per meter at distance 1, y = allowed error in pixels (0: LOD0 only)
  vec4 prune;           // x = distance where d reaches 1 (m), y = transition band t, z = fixed λ or target Q, w = fixed s
  vec4 lod_camera;      // xyz the point branch LODs and λ are chosen from: the camera, unless frozen
  mat4 prev_view_proj;  // the frame the depth pyramid was built from
  mat4 prev_inv_view_proj;  // its inverse: pyramid texels back to world points (receiver_mask.comp)
  vec4 prev_camera;     // xyz its camera position, w its near plane (m)
  vec4 pyramid;         // x, y = level-0 size in texels, z = level count
  uint instance_count;
  uint leaf_command_base;  // index of the first leaf command in the command buffer
  uint prune_mode;         // PRUNE_*
  uint view_flags;         // VIEW_*
  uint occlusion;          // OCCLUSION_*
  uint tail_capacity;      // entries of the tail leaf buffer (BINDING_TAIL_LEAVES)
  uint tail_job_capacity;  // TailJobs per frame: instances, at most maxComputeWorkGroupCount[0]
  uint shadows;            // 1: the shadow pass ran, shaders sample the shadow map
  // Sun shadows (shadow_pass.h, shadow_cascades.h). Cascade c covers view depths up to
  // shadow_splits[c] (metres along camera_forward); its light-space matrix maps world points
  // to [-1, 1]² × [0, 1] depth (0 toward the sun).
  mat4 shadow_view_proj[SHADOW_CASCADES];
  vec4 shadow_planes[SHADOW_CASCADES * 6];  // each cascade's caster volume, as frustum[]
  vec4 shadow_splits;   // xyz = far view depth of cascades 0..2, w = shadow distance
  vec4 shadow_texel;    // xyz = world size of one texel of cascades 0..2, w = texels per side
  vec4 camera_forward;  // xyz unit view direction (view depth = dot(p − camera_pos, it))
  vec4 light;           // x = exposure (scene-linear multiplier before the tone map)
  // Impostor bake renders (VIEW_IMPOSTOR_NORMAL): x = view depth of the model's sphere centre,
  // y = 1 / (2 · its radius): height 0.5 + (x − view depth) · y, 1 toward the camera.
  // z > 0: the coverage cutoff every impostor uses this frame instead of its model's (the
  // bake's search for it).
  vec4 impostor;
  uint impostors;       // IMPOSTORS_*
  uint receiver_mask;   // 1: shadow_cull.comp skips casters no visible receiver needs (BINDING_RECEIVER_MASK)
  uint frame_pad1, frame_pad2;
};

// Push constants of the tree and terrain vertex shaders: where a draw's commands start and
// which camera projects it. The camera's own draws use frame.view_proj (cascade SHADOW_NONE);
// the shadow pass draws each cascade with frame.shadow_view_proj[cascade]. Placed after
// PrCountPush (28 bytes) so the compute and vertex ranges of the shared layout do not overlap.
#define DRAW_PUSH_OFFSET 32
struct DrawPush {
  uint command_base;  // index of the draw's first DrawCommand (gl_DrawID counts from it)
  uint cascade;       // SHADOW_NONE, or the cascade being drawn
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
  vec4 bark_color;           // linear rgb, times the bark albedo texture (white when it holds the colour)
  vec4 leaf_color;           // linear rgb
  // The corners of the triangle around the leaf card (scene_buffers.cpp, leaf_triangle), in
  // the order leaf_card.geom emits them: xy = card position (z = 0, normal
  // +Z), zw = uv, which runs past the texture's unit square (cut by the fragment shaders);
  // [3] unused.
  vec4 card_corners[4];
  // Branch LOD chain: [0] full detail; lod_error = model-space error in meters, non-decreasing.
  uint lod_first_index[MAX_BRANCH_LODS];
  uint lod_index_count[MAX_BRANCH_LODS];
  int lod_vertex_offset[MAX_BRANCH_LODS];
  float lod_error[MAX_BRANCH_LODS];
  uint lod_count;
  uint leaf_texture_layer;
  uint card_first_index;     // the one leaf card mesh of this model
  uint card_index_count;
  int card_vertex_offset;
  uint leaf_offset;          // first leaf of this model in leaves[]
  uint leaf_count;
  uint table_offset;         // first float of this model's PR tables in the prune table buffer
  uint has_tables;           // 0: not baked; mode opt then draws it at full detail
  uint sample_offset;        // first HullSample of this model
  uint sample_count;
  float occlusion_margin;    // model-space meters a sample is moved toward the camera before the test
  float card_radius;         // farthest vertex of the leaf card from its origin (leaf scale 1)
  uint bark_texture_layer;   // layer of BINDING_BARK_ALBEDO / _NORMALS (0: neutral, untextured)
  // κ (1/m) of the baked crown depths (Leaf::crown_depth, shaders/crown_light.h); 0: none
  // baked, leaf.vert then uses the exit distance from the bounding sphere with a default κ.
  float crown_extinction;
  float pr_size0;            // projected size (px across the bounding sphere) of the tables' size 0
  uint leaf_quad_first_index;  // the shared index pattern: a quad, then the pulled leaves' points
  uint impostor_layer;       // layer of BINDING_IMPOSTOR_ALBEDO / _NORMALS; 0: no impostor
  float impostor_cutoff;     // blended coverage from which an impostor pixel shows the tree (baked)
  // Q of the impostor against full detail at the PR table sizes (pr_size0 / 2^b), baked.
  float impostor_q[PR_SIZES];
};

// One occlusion sample point on the model's hull (bake) or, unbaked, on its bounding sphere.
GPU_STRUCT HullSample {
  vec4 position;  // model space, w = 1
  vec4 normal;    // outward unit normal, w = 0
};

// Per-instance occlusion feedback, read and rewritten by cull.comp every frame.
GPU_STRUCT InstanceState {
  float occlusion;  // smoothed factor o in [OCCLUSION_FLOOR, 1]: λ = λ_mode(d) · o
  float visible;    // last measured fraction f of front-facing samples that were visible
  uint occluded;    // 1: culled outright last frame (no visible sample, hidden sphere)
  uint pad;
};

// One leaf: an instance of the model's leaf card (glTF EXT_mesh_gpu_instancing TRS).
GPU_STRUCT Leaf {
  vec4 position_scale;  // model space position, w = uniform scale
  vec4 rotation;        // unit quaternion xyzw
  vec4 color;           // rgb multiplier of the model's leaf color
  // Baked depth below the crown's hull (metres, model space) as packHalf2x16 pairs:
  // x = (+x, −x), y = (+y, −y), z = (+z, −z), w = 0 (shaders/crown_light.h). Zero when unbaked.
  uvec4 crown_depth;
};

// One partly occluded tree whose leaves [first_leaf, end_leaf) of the mode's prefix are
// tested one by one against the depth pyramid by tail_cull.comp (indices into leaves[]).
struct TailJob {
  uint command;     // its leaf draw, whose instance_count tail_cull.comp fills in
  uint first_leaf;
  uint end_leaf;
  uint base;        // first entry reserved for it in the tail leaf buffer
};

// DrawCommand.leaf_list: where a leaf draw finds its leaves.
#define LEAF_LIST_DIRECT 0  // the draw's item (instance, or pulled vertex / 4) is the leaf (a prefix of the model's leaves)
#define LEAF_LIST_TAIL 1    // the item indexes the tail leaf buffer, which holds the leaf

// VkDrawIndexedIndirectCommand followed by the tree instance the draw belongs to.
struct DrawCommand {
  uint index_count;
  uint instance_count;
  uint first_index;
  int vertex_offset;
  uint first_instance;
  uint instance;
  float lambda;        // detail level the leaf sizes and the transition band follow
  float area_scale;    // s: leaf area scale compensating the dropped leaves
  float shown_lambda;  // λ the λ view colours the tree by (with occlusion: λ · o)
  uint leaf_list;      // LEAF_LIST_*
  float fade;          // fraction of the tree's pixels this mesh draws (dithered; the impostor the rest)
};

// One far tree drawn as an impostor: its instance and the fraction of its pixels the
// impostor draws (the cross-fade with its mesh, dithered).
struct ImpostorEntry {
  uint instance;
  float fade;
};

// VkDrawIndexedIndirectCommand of the impostor quads of one list: one instance per listed
// tree, the 6 indices of the shared quad pattern (LEAF_QUAD_INDICES, Model.leaf_quad_first_index).
struct ImpostorDraw {
  uint index_count;
  uint instance_count;
  uint first_index;
  int vertex_offset;
  uint first_instance;
};

// Counters written by cull.comp, read by vkCmdDrawIndexedIndirectCount.
struct DrawCounts {
  uint branch_draws;
  uint leaf_draws;
  uint leaves_drawn;
  uint branch_triangles;
  uint lod_draws[MAX_BRANCH_LODS];  // branch draws per LOD level
  uint lambda_sum;                  // Σ λ over visible trees, in 1/4096 (mean λ)
  uint occluded_instances;          // in the frustum but culled by occlusion
  uint leaves_saved;                // leaves the mode would draw minus leaves drawn (occlusion)
  uint triangles_saved;             // leaf + branch triangles saved by occlusion
  // VkDispatchIndirectCommand of tail_cull.comp: one workgroup per TailJob.
  uint tail_jobs;
  uint tail_groups_y, tail_groups_z;  // 1, written by cull.comp
  uint tail_leaves;                   // tail leaf buffer entries reserved (may pass the capacity)
  // shadow_cull.comp, per cascade: branch draws (= caster trees), leaf draws, and triangles.
  uint shadow_branch_draws[SHADOW_CASCADES];
  uint shadow_leaf_draws[SHADOW_CASCADES];
  uint shadow_triangles[SHADOW_CASCADES];
  uint shadow_leaves[SHADOW_CASCADES];
  // The impostor draws of the camera and of each cascade (impostor_pass.h); vertex counts
  // written by cull.comp.
  ImpostorDraw impostor_draws[IMPOSTOR_LISTS];
};

// Pixel counts of one coverage comparison (pr_count.comp).
struct PrCounts {
  uint tp;  // covered in both
  uint fp;  // covered only by the test (pruned) frame
  uint fn;  // covered only by the reference (full) frame
  uint pad;
};

// Push constants of pr_count.comp. Offsets are in pixels into the coverage reference
// buffer, which holds one full-detail reference per view and, for batched bake
// measurements, the branch-only coverage of that view: the pruned frame then draws only
// leaves and its coverage is OR-ed with the branch mask (the same union the full draw
// would produce, since coverage writes a constant white regardless of depth order).
#define PR_NO_MASK 0xffffffffu
struct PrCountPush {
  uint pixel_count;
  uint reference_offset;
  uint branch_offset;  // PR_NO_MASK: the test frame already holds the branches
  uint result;         // index into the PrCounts array; with lattices, of its first of PR_SIZES
  uint width;          // pixels per row (lattices)
  uint lattices;       // 1: frames from SPEC_COVERAGE_LATTICES, counted per PR size
  // Lattices only: PR_NO_MASK, or the index of the first of PR_PHASE_BINS counts per sub-pixel
  // phase, each one what a render at size b >= 1 at that phase counts (prune::phase_bin).
  uint phase_result;
};
// Size b has 4^b sub-pixel phases: bins (4^b − 1)/3 … (4^(b+1) − 1)/3 − 1 (bin 0, size 0's
// only phase, stays empty: it is the size's total).
#define PR_PHASE_BINS ((1u << (2u * PR_SIZES)) / 3u)

// Push constants of depth_pyramid.comp: one level's reduction.
struct DepthPyramidPush {
  ivec2 source_size;       // texels of the source (the depth buffer or the level above)
  ivec2 destination_size;  // texels of the level written
  uint first_level;        // 1: the source is the depth buffer
  uint pad;                // std430 rounds the struct up to its 8-byte alignment
};

// Push constants of present.frag: the viewport rectangle the frame is scaled into, in pixels.
struct PresentPush {
  vec2 offset;
  vec2 size;
};

#ifdef __cplusplus
}  // namespace forest::gpu
#undef GPU_STRUCT
#endif
#endif
