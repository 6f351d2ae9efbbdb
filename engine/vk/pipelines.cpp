#include "engine/vk/pipelines.h"

#include <cstddef>
#include <iterator>
#include <string>

#include "generators/model/tree_model.h"
#include "gpu_types.h"

namespace forest::vk {

namespace {

const VkVertexInputAttributeDescription kVertexAttributes[] = {
    {ATTR_POSITION, 0, VK_FORMAT_R32G32B32_SFLOAT, uint32_t(offsetof(Vertex, position))},
    {ATTR_NORMAL, 0, VK_FORMAT_R32G32B32_SFLOAT, uint32_t(offsetof(Vertex, normal))},
    {ATTR_UV, 0, VK_FORMAT_R32G32_SFLOAT, uint32_t(offsetof(Vertex, uv))},
};

}  // namespace

std::span<const VkVertexInputAttributeDescription> vertex_attributes() { return kVertexAttributes; }

VkShaderModule create_shader(Context& ctx, std::string_view name) {
  std::span<const uint32_t> code = shaders::find(name);
  if (code.empty()) throw VkFailure("shader not compiled into the executable: " + std::string(name));
  VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  ci.codeSize = code.size_bytes();
  ci.pCode = code.data();
  VkShaderModule module;
  VK_CHECK(vkCreateShaderModule(ctx.device, &ci, nullptr, &module));
  return module;
}

VkPipelineLayout create_pipeline_layout(Context& ctx, VkDescriptorSetLayout set, std::span<const VkPushConstantRange> push) {
  VkPipelineLayoutCreateInfo plci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  plci.setLayoutCount = 1;
  plci.pSetLayouts = &set;
  plci.pushConstantRangeCount = uint32_t(push.size());
  plci.pPushConstantRanges = push.data();
  VkPipelineLayout layout;
  VK_CHECK(vkCreatePipelineLayout(ctx.device, &plci, nullptr, &layout));
  return layout;
}

namespace {

VkPipelineColorBlendAttachmentState blend_state(const GraphicsPipelineDesc& desc) {
  VkPipelineColorBlendAttachmentState b{};
  b.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                     (desc.write_alpha ? VkColorComponentFlags(VK_COLOR_COMPONENT_A_BIT) : 0u);
  if (desc.blend_max) {
    b.blendEnable = VK_TRUE;
    b.srcColorBlendFactor = b.dstColorBlendFactor = VK_BLEND_FACTOR_ONE;
    b.srcAlphaBlendFactor = b.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
    b.colorBlendOp = b.alphaBlendOp = VK_BLEND_OP_MAX;
  }
  return b;
}

VkPipelineShaderStageCreateInfo stage(VkShaderStageFlagBits bit, VkShaderModule module,
                                      const VkSpecializationInfo* specialization = nullptr) {
  return {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, bit, module, "main", specialization};
}

}  // namespace

VkPipeline create_graphics_pipeline(Context& ctx, VkPipelineLayout layout, const GraphicsPipelineDesc& desc) {
  VkShaderModule vs = create_shader(ctx, desc.vertex);
  VkShaderModule fs = desc.fragment.empty() ? VK_NULL_HANDLE : create_shader(ctx, desc.fragment);
  VkShaderModule gs = desc.geometry.empty() ? VK_NULL_HANDLE : create_shader(ctx, desc.geometry);
  std::vector<VkSpecializationMapEntry> entries;
  std::vector<uint32_t> values;
  for (const SpecConstant& c : desc.fragment_specialization) {
    entries.push_back({c.id, uint32_t(values.size() * sizeof(uint32_t)), sizeof(uint32_t)});
    values.push_back(c.value);
  }
  VkSpecializationInfo specialization{uint32_t(entries.size()), entries.data(), values.size() * sizeof(uint32_t),
                                      values.data()};
  VkPipelineShaderStageCreateInfo stages[3] = {stage(VK_SHADER_STAGE_VERTEX_BIT, vs)};
  uint32_t stage_count = 1;
  if (gs) stages[stage_count++] = stage(VK_SHADER_STAGE_GEOMETRY_BIT, gs);
  if (fs) stages[stage_count++] = stage(VK_SHADER_STAGE_FRAGMENT_BIT, fs, entries.empty() ? nullptr : &specialization);

  VkVertexInputBindingDescription binding{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX};
  VkPipelineVertexInputStateCreateInfo vertex_input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  if (desc.vertex_input) {
    vertex_input.vertexBindingDescriptionCount = 1;
    vertex_input.pVertexBindingDescriptions = &binding;
    vertex_input.vertexAttributeDescriptionCount = uint32_t(std::size(kVertexAttributes));
    vertex_input.pVertexAttributeDescriptions = kVertexAttributes;
  }
  VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = desc.topology;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = desc.polygon_mode;
  raster.cullMode = desc.cull;
  raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  raster.lineWidth = 1.0f;
  raster.depthBiasEnable = desc.depth_bias_constant != 0.0f || desc.depth_bias_slope != 0.0f;
  raster.depthBiasConstantFactor = desc.depth_bias_constant;
  raster.depthBiasSlopeFactor = desc.depth_bias_slope;
  VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = desc.samples;
  VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  depth.depthTestEnable = desc.depth_test;
  depth.depthWriteEnable = desc.depth_write;
  depth.depthCompareOp = desc.depth_compare;
  VkPipelineColorBlendAttachmentState blend_attachment = blend_state(desc);
  VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  const bool color = desc.color_format != VK_FORMAT_UNDEFINED;
  blend.attachmentCount = color ? 1 : 0;
  blend.pAttachments = &blend_attachment;
  VkDynamicState dynamic_states[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamic.dynamicStateCount = 2;
  dynamic.pDynamicStates = dynamic_states;

  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  rendering.colorAttachmentCount = color ? 1 : 0;
  rendering.pColorAttachmentFormats = &desc.color_format;
  rendering.depthAttachmentFormat = desc.depth_format;

  VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
  ci.stageCount = stage_count;
  ci.pStages = stages;
  ci.pVertexInputState = &vertex_input;
  ci.pInputAssemblyState = &assembly;
  ci.pViewportState = &viewport;
  ci.pRasterizationState = &raster;
  ci.pMultisampleState = &multisample;
  ci.pDepthStencilState = &depth;
  ci.pColorBlendState = &blend;
  ci.pDynamicState = &dynamic;
  ci.layout = layout;
  VkPipeline pipeline;
  VK_CHECK(vkCreateGraphicsPipelines(ctx.device, VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline));
  for (VkShaderModule module : {vs, gs, fs})
    if (module) vkDestroyShaderModule(ctx.device, module, nullptr);
  return pipeline;
}

bool pull_leaves(const Context& ctx, GraphicsPipelineDesc& leaves, std::string_view vertex) {
  if (!ctx.geometry_shader) return false;
  leaves.vertex = vertex;
  leaves.geometry = "leaf_card_geom";
  leaves.topology = VK_PRIMITIVE_TOPOLOGY_POINT_LIST;
  leaves.vertex_input = false;
  return true;
}

VkPipeline create_compute_pipeline(Context& ctx, VkPipelineLayout layout, std::string_view shader,
                                   VkPipelineShaderStageCreateFlags stage_flags) {
  VkShaderModule cs = create_shader(ctx, shader);
  VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, stage_flags, VK_SHADER_STAGE_COMPUTE_BIT, cs,
              "main"};
  ci.layout = layout;
  VkPipeline pipeline;
  VK_CHECK(vkCreateComputePipelines(ctx.device, VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline));
  vkDestroyShaderModule(ctx.device, cs, nullptr);
  return pipeline;
}

}  // namespace forest::vk
