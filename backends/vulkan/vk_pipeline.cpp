// A graphics pipeline from the device's fixed state: dynamic rendering, dynamic
// viewport and scissor, Bresenham lines where the platform has them.
#include "backends/vulkan/vk_pipeline.h"

#include <string>
#include <vector>

#include "backends/vulkan/vk_util.h"

namespace sb {

VkPipeline createGraphicsPipeline(const VulkanPlatform& platform, const PipelineDesc& desc,
                                  VkPipelineLayout layout, VkShaderModule vs, VkShaderModule fs) {
  VkPipelineShaderStageCreateInfo stages[2] = {
      {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
      {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
  // A mesh pipeline's mesh shader stands in for the vertex stage (no vertex input).
  const bool mesh = desc.vertex->meshGroupVertices > 0;
  stages[0].stage = mesh ? VK_SHADER_STAGE_MESH_BIT_EXT : VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vs;
  stages[0].pName = "main";
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = fs;
  stages[1].pName = "main";

  VkPipelineVertexInputStateCreateInfo vi{
      VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  VkPipelineInputAssemblyStateCreateInfo ia{
      VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  const bool lines = desc.topology == Topology::Lines;
  ia.topology = lines ? VK_PRIMITIVE_TOPOLOGY_LINE_LIST : VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo vps{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  vps.viewportCount = 1;
  vps.scissorCount = 1;
  VkPipelineRasterizationLineStateCreateInfoEXT lineState{
      VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_LINE_STATE_CREATE_INFO_EXT};
  lineState.lineRasterizationMode = VK_LINE_RASTERIZATION_MODE_BRESENHAM_EXT;
  VkPipelineRasterizationStateCreateInfo rs{
      VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  rs.pNext = lines && platform.bresenham ? &lineState : nullptr;
  rs.polygonMode = VK_POLYGON_MODE_FILL;
  rs.cullMode = VK_CULL_MODE_NONE;
  rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  rs.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  // The pass's sample count (the front end checks they match); the bit value
  // of VkSampleCountFlagBits is the count.
  ms.rasterizationSamples = static_cast<VkSampleCountFlagBits>(desc.samples);
  VkPipelineDepthStencilStateCreateInfo ds{
      VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  ds.depthTestEnable = desc.hasDepth && desc.depthTest;
  ds.depthWriteEnable = desc.hasDepth && desc.depthWrite;
  ds.depthCompareOp = toVk(desc.depthCompare);

  if (desc.logicOpOr && !platform.logicOp) {
    throw DeviceError("createPipeline('" + desc.name + "', technique '" + desc.technique +
                      "'): logic-op OR needs the logicOp feature, which " + platform.info.device +
                      " lacks");
  }
  std::vector<VkPipelineColorBlendAttachmentState> blends;
  for (std::size_t i = 0; i < desc.colorFormats.size(); ++i) {
    const Format f = desc.colorFormats[i];
    const BlendState b = i < desc.blend.size() ? desc.blend[i] : BlendState::replace();
    VkPipelineColorBlendAttachmentState a{};
    a.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                       VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    // Integer targets never blend; with a logic op, blending is ignored anyway.
    a.blendEnable = b.enable && !isIntegerFormat(f) && !desc.logicOpOr;
    if (a.blendEnable) {
      VkFormatProperties fp;
      vkGetPhysicalDeviceFormatProperties(platform.physical, toVkFormat(f), &fp);
      if ((fp.optimalTilingFeatures & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT) == 0) {
        throw DeviceError("createPipeline('" + desc.name + "', technique '" + desc.technique +
                          "'): format " + formatName(f) + " cannot blend on " +
                          platform.info.device);
      }
    }
    a.srcColorBlendFactor = toVk(b.srcColor);
    a.dstColorBlendFactor = toVk(b.dstColor);
    a.colorBlendOp = toVk(b.colorOp);
    a.srcAlphaBlendFactor = toVk(b.srcAlpha);
    a.dstAlphaBlendFactor = toVk(b.dstAlpha);
    a.alphaBlendOp = toVk(b.alphaOp);
    blends.push_back(a);
  }
  VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  cb.logicOpEnable = desc.logicOpOr ? VK_TRUE : VK_FALSE;
  cb.logicOp = VK_LOGIC_OP_OR;
  cb.attachmentCount = static_cast<uint32_t>(blends.size());
  cb.pAttachments = blends.data();

  const VkDynamicState dyn[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dy{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dy.dynamicStateCount = 2;
  dy.pDynamicStates = dyn;

  std::vector<VkFormat> colorFormats;
  for (Format f : desc.colorFormats) colorFormats.push_back(toVkFormat(f));
  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  rendering.colorAttachmentCount = static_cast<uint32_t>(colorFormats.size());
  rendering.pColorAttachmentFormats = colorFormats.data();
  rendering.depthAttachmentFormat =
      desc.hasDepth ? toVkFormat(desc.depthFormat) : VK_FORMAT_UNDEFINED;
  rendering.stencilAttachmentFormat = VK_FORMAT_UNDEFINED;

  VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
  ci.stageCount = 2;
  ci.pStages = stages;
  ci.pVertexInputState = mesh ? nullptr : &vi;
  ci.pInputAssemblyState = mesh ? nullptr : &ia;
  ci.pViewportState = &vps;
  ci.pRasterizationState = &rs;
  ci.pMultisampleState = &ms;
  ci.pDepthStencilState = &ds;
  ci.pColorBlendState = &cb;
  ci.pDynamicState = &dy;
  ci.layout = layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  check(vkCreateGraphicsPipelines(platform.device, VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline),
        "vkCreateGraphicsPipelines");
  return pipeline;
}

}  // namespace sb
