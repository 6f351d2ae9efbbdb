// The draw pass: sky, terrain, then the cull pass's indirect draws of bark (branch.vert) and
// leaf cards (leaf.vert), shaded by tree.frag, into the render targets. One recording path
// for every picture the renderer makes: frames, PR coverage references and batched PR bakes
// (coverage masks draw only trees, white, through the same pipelines).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "engine/render/cull_pass.h"
#include "engine/render/impostor_pass.h"
#include "engine/render/render_targets.h"
#include "engine/render/scene_buffers.h"
#include "engine/render/terrain_cull.h"

namespace forest {

struct DrawPipelines {
  VkPipeline sky = VK_NULL_HANDLE;  // fill only: every frame draws the sky through it
  VkPipeline terrain = VK_NULL_HANDLE, branches = VK_NULL_HANDLE;
  VkPipeline leaves = VK_NULL_HANDLE;            // vertex pulling (leaf_pulled.vert), no vertex input
  VkPipeline leaves_instanced = VK_NULL_HANDLE;  // instances of the card (leaf.vert): VIEW_LEAF_INSTANCED
};

struct DrawPass {
  DrawPipelines fill;   // the shaded picture: tree.frag without the other views (SPEC_VIEWS false)
  DrawPipelines views;  // every FrameData view (mask, λ, shadow visibility, impostor bake)
  DrawPipelines wire;  // edges only; null where the device lacks fillModeNonSolid
  // Bake coverage of the leaves at every PR size in one render (tree.frag, SPEC_COVERAGE_LATTICES):
  // no depth test, MAX blending. Single-sampled renderers only.
  VkPipeline lattice_leaves = VK_NULL_HANDLE, lattice_leaves_instanced = VK_NULL_HANDLE;
  // The bark of bake coverage, drawn once per PR size with that size's branch LOD, into the
  // channels that hold the size (tree_frag.glsl branch_lattice_coverage).
  VkPipeline lattice_branches = VK_NULL_HANDLE;
};

inline constexpr Binding kDrawBindings[] = {
    {BINDING_COMMANDS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_VERTEX_BIT},
    {BINDING_TAIL_LEAVES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_VERTEX_BIT},
    {BINDING_LEAF_TEXTURES, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT},
    {BINDING_BARK_ALBEDO, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT},
    {BINDING_BARK_NORMALS, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT},
};

// leaf_shadows_per_fragment: leaves read the shadow map per fragment, not once a leaf
// ([render] leaf_shadows = "fragment"; tree.frag, SPEC_LEAF_SHADOW_PER_FRAGMENT).
DrawPass create_draw_pass(vk::Context& ctx, VkPipelineLayout layout, VkSampleCountFlagBits samples,
                          bool leaf_shadows_per_fragment);
void destroy_draw_pass(vk::Context& ctx, DrawPass& pass);

// What one recording draws.
struct DrawList {
  bool background = true;  // sky and terrain (false: coverage, cleared to black)
  bool branches = true;
  bool leaves = true;
  bool wireframe = false;   // the wire pipelines (must exist)
  bool keep_depth = false;  // store the depth (or its resolve) for the depth pyramid
  bool shadows = false;     // the shadow pass runs first (shadow_pass.h); never in coverage frames
  bool receiver_mask = false;  // shadows: the receiver mask is made first (FrameData.receiver_mask)
  bool lattices = false;    // coverage frames of the bake: leaves through DrawPass::lattice_leaves,
                            // branches through lattice_branches at the size FrameData.lod.z
  bool keep_color = false;  // load the colour attachment (a frame drawn in several passes), not clear it
  bool instanced_leaves = false;  // the cull pass wrote instanced leaf draws (VIEW_LEAF_INSTANCED)
  bool impostors = false;         // the cull pass may have listed impostors (impostor_pass.h)
  bool views = false;  // FrameData.view_flags asks for a view other than the shaded picture
  std::vector<IndexRange> terrain;  // with a background: the terrain chunks the camera sees
  std::array<std::vector<IndexRange>, SHADOW_CASCADES> shadow_terrain;  // with shadows: each cascade's
};

// Whether a frame with these FrameData.view_flags draws through DrawPass::views: every flag
// but the leaf draw's form is a view that the shaded pipelines do not read.
inline bool draws_a_view(uint32_t view_flags) { return (view_flags & ~uint32_t(VIEW_LEAF_INSTANCED)) != 0; }

// Records the draw (set 0 bound to the graphics bind point by the caller). Before: the cull
// pass's writes are visible to indirect and vertex reads. After: the colour image is in
// COLOR_ATTACHMENT_OPTIMAL with its writes done at COLOR_ATTACHMENT_OUTPUT; depth likewise
// at the fragment tests.
void record_draw_pass(VkCommandBuffer cmd, const DrawPass& pass, VkPipelineLayout layout, VkDescriptorSet set,
                      const SceneBuffers& scene, const CullPass& cull, const ImpostorPass& impostors,
                      const RenderTargets& targets, const DrawList& list);

}  // namespace forest
