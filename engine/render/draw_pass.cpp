#include "engine/render/draw_pass.h"

#include "engine/render/shadow_pass.h"
#include "engine/vk/pipelines.h"

namespace forest {

namespace {

// views: tree.frag reads FrameData.view_flags (SPEC_VIEWS); the shaded picture's pipelines do not.
DrawPipelines create_pipelines(vk::Context& ctx, VkPipelineLayout layout, VkSampleCountFlagBits samples, bool wire,
                              bool leaf_shadows_per_fragment, bool views) {
  vk::GraphicsPipelineDesc d;
  d.color_format = kColorFormat;
  d.depth_format = kDepthFormat;
  d.samples = samples;
  if (wire) {
    d.polygon_mode = VK_POLYGON_MODE_LINE;
    d.cull = VK_CULL_MODE_NONE;
  }
  DrawPipelines p;
  if (!wire && !views) {  // one sky for every frame: DrawPass::fill's (record_draw_pass)
    vk::GraphicsPipelineDesc sky = d;
    sky.vertex = "sky_vert";
    sky.fragment = "sky_frag";
    sky.vertex_input = false;
    sky.cull = VK_CULL_MODE_NONE;
    sky.depth_test = false;
    sky.depth_write = false;
    p.sky = vk::create_graphics_pipeline(ctx, layout, sky);
  }
  vk::GraphicsPipelineDesc terrain = d;
  terrain.vertex = "terrain_vert";
  terrain.fragment = "terrain_frag";
  p.terrain = vk::create_graphics_pipeline(ctx, layout, terrain);
  vk::GraphicsPipelineDesc branches = d;
  branches.vertex = "branch_vert";
  branches.fragment = "tree_frag";
  branches.fragment_specialization = {{SPEC_VIEWS, views ? 1u : 0u}};
  p.branches = vk::create_graphics_pipeline(ctx, layout, branches);
  vk::GraphicsPipelineDesc leaves = branches;
  leaves.vertex = "leaf_vert";
  if (!wire) {
    leaves.cull = VK_CULL_MODE_NONE;  // leaf cards are two-sided
    leaves.fragment_specialization.push_back({SPEC_LEAF, 1u});
    leaves.fragment_specialization.push_back({SPEC_LEAF_SHADOW_PER_FRAGMENT, leaf_shadows_per_fragment ? 1u : 0u});
    if (samples > VK_SAMPLE_COUNT_1_BIT) {  // the leaf alpha becomes a sample mask (leaf_msaa.frag)
      leaves.fragment = "leaf_msaa_frag";
      leaves.fragment_specialization.push_back({SPEC_COVERAGE_SAMPLES, uint32_t(samples)});
    }
    // A leaf's coverage is never opacity: when alpha-to-coverage's alpha was written to the
    // attachment it made the resolved frame translucent at every leaf edge, and a PNG viewer
    // showed its page background (white) through the crowns. The sky underneath writes alpha 1.
    leaves.write_alpha = false;
  }
  p.leaves_instanced = vk::create_graphics_pipeline(ctx, layout, leaves);
  // The wireframe view draws leaves instanced (Renderer::frame_data).
  if (!wire && vk::pull_leaves(ctx, leaves)) p.leaves = vk::create_graphics_pipeline(ctx, layout, leaves);
  return p;
}

void destroy_pipelines(vk::Context& ctx, DrawPipelines& p) {
  for (VkPipeline pipeline : {p.sky, p.terrain, p.branches, p.leaves, p.leaves_instanced})
    vkDestroyPipeline(ctx.device, pipeline, nullptr);
  p = {};
}

// The targets become attachments; also after the previous frame's pyramid reads of the
// depth (compute) and the copies out of the colour image (transfer).
void begin_targets(VkCommandBuffer cmd, const RenderTargets& t, bool keep_color) {
  vk::image_barrier(cmd, t.color.image, VK_IMAGE_ASPECT_COLOR_BIT,
                    keep_color ? VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL : VK_IMAGE_LAYOUT_UNDEFINED,
                    VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                    VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                        VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  if (t.color_msaa.image)
    vk::image_barrier(cmd, t.color_msaa.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                      VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                      VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                      VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  const VkPipelineStageFlags2 tests =
      VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
  for (VkImage image : {t.depth.image, t.depth_resolve.image})
    if (image)
      vk::image_barrier(cmd, image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                        VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                        tests | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                        VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                        tests | VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                        VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                            VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
}

void begin_rendering(VkCommandBuffer cmd, const RenderTargets& t, const DrawList& list) {
  VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  color.imageView = t.color.view;
  color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  // With a background the sky covers every pixel.
  color.loadOp = list.background   ? VK_ATTACHMENT_LOAD_OP_DONT_CARE
                 : list.keep_color ? VK_ATTACHMENT_LOAD_OP_LOAD
                                   : VK_ATTACHMENT_LOAD_OP_CLEAR;
  // Opaque: leaves write no alpha; bake coverage keeps a PR size in alpha (tree_frag.glsl).
  color.clearValue.color = {{0.0f, 0.0f, 0.0f, list.lattices ? 0.0f : 1.0f}};
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  if (t.color_msaa.image) {  // render multisampled, resolve (average) into the single-sample image
    color.imageView = t.color_msaa.view;
    color.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    color.resolveMode = VK_RESOLVE_MODE_AVERAGE_BIT;
    color.resolveImageView = t.color.view;
    color.resolveImageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  }
  VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  depth.imageView = t.depth.view;
  depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  // Kept when the depth pyramid reads it (single-sampled), else resolved into depth_resolve.
  depth.storeOp = list.keep_depth && !t.depth_resolve.image ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE;
  depth.clearValue.depthStencil = {0.0f, 0};  // reversed Z: 0 is infinitely far
  if (t.depth_resolve.image) {
    depth.resolveMode = VK_RESOLVE_MODE_SAMPLE_ZERO_BIT;
    depth.resolveImageView = t.depth_resolve.view;
    depth.resolveImageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  }
  VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
  ri.renderArea = {{0, 0}, t.extent};
  ri.layerCount = 1;
  ri.colorAttachmentCount = 1;
  ri.pColorAttachments = &color;
  ri.pDepthAttachment = &depth;
  vkCmdBeginRendering(cmd, &ri);
  VkViewport viewport{0.0f, 0.0f, float(t.extent.width), float(t.extent.height), 0.0f, 1.0f};
  VkRect2D scissor{{0, 0}, t.extent};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
}

}  // namespace

DrawPass create_draw_pass(vk::Context& ctx, VkPipelineLayout layout, VkSampleCountFlagBits samples,
                          bool leaf_shadows_per_fragment) {
  DrawPass p;
  p.fill = create_pipelines(ctx, layout, samples, false, leaf_shadows_per_fragment, false);
  p.views = create_pipelines(ctx, layout, samples, false, leaf_shadows_per_fragment, true);
  if (samples == VK_SAMPLE_COUNT_1_BIT) {
    vk::GraphicsPipelineDesc d;
    d.color_format = kColorFormat;
    d.depth_format = kDepthFormat;
    d.vertex = "leaf_vert";
    d.fragment = "tree_frag";
    d.cull = VK_CULL_MODE_NONE;
    d.depth_test = false;
    d.depth_write = false;
    d.blend_max = true;
    d.fragment_specialization = {{SPEC_LEAF, 1u}, {SPEC_COVERAGE_LATTICES, 1u}};
    p.lattice_leaves_instanced = vk::create_graphics_pipeline(ctx, layout, d);
    if (vk::pull_leaves(ctx, d)) p.lattice_leaves = vk::create_graphics_pipeline(ctx, layout, d);
    d.vertex = "branch_vert";
    d.geometry = {};
    d.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    d.vertex_input = true;
    d.cull = VK_CULL_MODE_BACK_BIT;
    d.fragment_specialization = {{SPEC_COVERAGE_LATTICES, 1u}};
    p.lattice_branches = vk::create_graphics_pipeline(ctx, layout, d);
  }
  if (ctx.fill_mode_non_solid) p.wire = create_pipelines(ctx, layout, samples, true, leaf_shadows_per_fragment, true);
  return p;
}

void destroy_draw_pass(vk::Context& ctx, DrawPass& p) {
  destroy_pipelines(ctx, p.fill);
  destroy_pipelines(ctx, p.views);
  destroy_pipelines(ctx, p.wire);
  vkDestroyPipeline(ctx.device, p.lattice_leaves, nullptr);
  vkDestroyPipeline(ctx.device, p.lattice_leaves_instanced, nullptr);
  vkDestroyPipeline(ctx.device, p.lattice_branches, nullptr);
  p.lattice_leaves = p.lattice_leaves_instanced = p.lattice_branches = VK_NULL_HANDLE;
}

void record_draw_pass(VkCommandBuffer cmd, const DrawPass& pass, VkPipelineLayout layout, VkDescriptorSet set,
                      const SceneBuffers& scene, const CullPass& cull, const ImpostorPass& impostors,
                      const RenderTargets& targets, const DrawList& list) {
  const DrawPipelines& p = list.wireframe ? pass.wire : list.views ? pass.views : pass.fill;
  begin_targets(cmd, targets, list.keep_color);
  begin_rendering(cmd, targets, list);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &set, 0, nullptr);
  VkDeviceSize zero = 0;
  vkCmdBindVertexBuffers(cmd, 0, 1, &scene.vertices.buffer, &zero);
  vkCmdBindIndexBuffer(cmd, scene.indices.buffer, 0, VK_INDEX_TYPE_UINT32);
  const uint32_t n = cull.instance_count, stride = sizeof(gpu::DrawCommand);
  auto push = [&](uint32_t command_base) {
    gpu::DrawPush dp{command_base, SHADOW_NONE};
    vkCmdPushConstants(cmd, layout, kDrawPushRange.stageFlags, kDrawPushRange.offset, sizeof(dp), &dp);
  };
  push(0);
  if (list.background) {  // the sky is filled in the wireframe view too
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pass.fill.sky);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p.terrain);
    for (const IndexRange& r : list.terrain) vkCmdDrawIndexed(cmd, r.count, 1, r.first, 0, 0);
  }
  if (n > 0 && list.branches) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, list.lattices ? pass.lattice_branches : p.branches);
    vkCmdDrawIndexedIndirectCount(cmd, cull.commands.buffer, 0, cull.counts.buffer,
                                  offsetof(gpu::DrawCounts, branch_draws), n, stride);
  }
  if (n > 0 && list.leaves) {  // up to two leaf draws per tree: the prefix and the occlusion tail
    push(n);
    VkPipeline leaves = list.lattices ? (list.instanced_leaves ? pass.lattice_leaves_instanced : pass.lattice_leaves)
                                      : (list.instanced_leaves ? p.leaves_instanced : p.leaves);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, leaves);
    vkCmdDrawIndexedIndirectCount(cmd, cull.commands.buffer, VkDeviceSize(n) * stride, cull.counts.buffer,
                                  offsetof(gpu::DrawCounts, leaf_draws), 2 * n, stride);
  }
  if (n > 0 && list.impostors && !list.lattices) record_impostor_draw(cmd, impostors, layout, cull, SHADOW_NONE);
  vkCmdEndRendering(cmd);
}

}  // namespace forest
