#include "geometry_mesh.h"
#include "passes.h"
#include "spirv.h"
#include "vk_check.h"

#include <algorithm>
#include <array>

namespace brume::gpu {
namespace {

Result<RenderPassOwner> createRenderPass(const Device& device) {
    std::array<VkAttachmentDescription, 3> att{};
    for (int i = 0; i < 3; ++i) {
        VkAttachmentDescription& a = att[static_cast<size_t>(i)];
        a.samples = VK_SAMPLE_COUNT_1_BIT;
        a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        a.storeOp = i < 2 ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE;
        a.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
        a.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        a.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        // The composite reads the colour attachments as storage images.
        a.finalLayout = i < 2 ? VK_IMAGE_LAYOUT_GENERAL : VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    }
    att[0].format = VK_FORMAT_R32G32B32A32_SFLOAT;
    att[1].format = VK_FORMAT_R32_SFLOAT;
    att[2].format = VK_FORMAT_D32_SFLOAT;
    const std::array<VkAttachmentReference, 2> colors{{{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL},
                                                       {1, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL}}};
    const VkAttachmentReference depth{2, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    VkSubpassDescription sub{};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sub.colorAttachmentCount = 2;
    sub.pColorAttachments = colors.data();
    sub.pDepthStencilAttachment = &depth;
    const VkPipelineStageFlags attachmentStages =
        VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
        VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    const VkAccessFlags attachmentWrites =
        VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    const std::array<VkSubpassDependency, 2> deps{{
        // The previous render's composite and copies must finish reading before the clear.
        {VK_SUBPASS_EXTERNAL, 0, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
         attachmentStages, 0, attachmentWrites, 0},
        {0, VK_SUBPASS_EXTERNAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
         VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT, 0},
    }};
    VkRenderPassCreateInfo info = vkStruct<VkRenderPassCreateInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO);
    info.attachmentCount = static_cast<uint32_t>(att.size());
    info.pAttachments = att.data();
    info.subpassCount = 1;
    info.pSubpasses = &sub;
    info.dependencyCount = static_cast<uint32_t>(deps.size());
    info.pDependencies = deps.data();
    VkRenderPass rp = VK_NULL_HANDLE;
    BRUME_VK(vkCreateRenderPass(device.vk(), &info, nullptr, &rp), "create the geometry render pass");
    device.name(rp, VK_OBJECT_TYPE_RENDER_PASS, "geometry render pass");
    return RenderPassOwner(device.vk(), rp);
}

// depthOnly: a pipeline of the depth pre-pass (no colour writes; fragment == nullptr: no fragment
// shader); otherwise a shading pipeline, tested EQUAL against the pre-pass's depth. The vertex shader
// reads GeometryVertex's first `attributes` vec4s.
Result<PipelineOwner> createPipeline(const Device& device, VkPipelineLayout layout, VkRenderPass renderPass,
                                     const SpecKey& key, const char* vertex, const char* fragment, bool depthOnly,
                                     uint32_t attributes = 4) {
    Result<ShaderModuleOwner> vert = createShaderModule(device, vertex);
    if (!vert) return vert.error();
    ShaderModuleOwner frag;
    if (fragment) {
        Result<ShaderModuleOwner> f = createShaderModule(device, fragment);
        if (!f) return f.error();
        frag = std::move(f.value());
    }
    const Specialization spec(key);
    std::array<VkPipelineShaderStageCreateInfo, 2> stages{};
    stages[0] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_VERTEX_BIT,
                 vert.value().get(), "main", &spec.info};
    stages[1] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_FRAGMENT_BIT,
                 frag.get(), "main", &spec.info};

    const VkVertexInputBindingDescription binding{0, sizeof(GeometryVertex), VK_VERTEX_INPUT_RATE_VERTEX};
    std::array<VkVertexInputAttributeDescription, 4> attrs{};
    for (uint32_t i = 0; i < 4; ++i) attrs[i] = {i, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 16 * i};
    VkPipelineVertexInputStateCreateInfo vertexInput = vkStruct<VkPipelineVertexInputStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO);
    vertexInput.vertexBindingDescriptionCount = 1;
    vertexInput.pVertexBindingDescriptions = &binding;
    vertexInput.vertexAttributeDescriptionCount = std::min(attributes, static_cast<uint32_t>(attrs.size()));
    vertexInput.pVertexAttributeDescriptions = attrs.data();
    VkPipelineInputAssemblyStateCreateInfo assembly = vkStruct<VkPipelineInputAssemblyStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO);
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo viewport = vkStruct<VkPipelineViewportStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO);
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo raster = vkStruct<VkPipelineRasterizationStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO);
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.cullMode = VK_CULL_MODE_NONE;  // surfaces are two-sided, as in the CPU's ray queries
    raster.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo multisample = vkStruct<VkPipelineMultisampleStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO);
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo depth = vkStruct<VkPipelineDepthStencilStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO);
    depth.depthTestEnable = VK_TRUE;
    depth.depthWriteEnable = depthOnly ? VK_TRUE : VK_FALSE;
    depth.depthCompareOp = depthOnly ? VK_COMPARE_OP_LESS : VK_COMPARE_OP_EQUAL;
    std::array<VkPipelineColorBlendAttachmentState, 2> blendAtt{};
    for (auto& b : blendAtt) b.colorWriteMask = depthOnly ? 0 : 0xF;
    VkPipelineColorBlendStateCreateInfo blend = vkStruct<VkPipelineColorBlendStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO);
    blend.attachmentCount = static_cast<uint32_t>(blendAtt.size());
    blend.pAttachments = blendAtt.data();
    const std::array<VkDynamicState, 2> dynamicStates{VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dynamic = vkStruct<VkPipelineDynamicStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO);
    dynamic.dynamicStateCount = static_cast<uint32_t>(dynamicStates.size());
    dynamic.pDynamicStates = dynamicStates.data();

    VkGraphicsPipelineCreateInfo info = vkStruct<VkGraphicsPipelineCreateInfo>(VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO);
    info.stageCount = fragment ? static_cast<uint32_t>(stages.size()) : 1;
    info.pStages = stages.data();
    info.pVertexInputState = &vertexInput;
    info.pInputAssemblyState = &assembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pDepthStencilState = &depth;
    info.pColorBlendState = &blend;
    info.pDynamicState = &dynamic;
    info.layout = layout;
    info.renderPass = renderPass;
    VkPipeline pipeline = VK_NULL_HANDLE;
    BRUME_VK(vkCreateGraphicsPipelines(device.vk(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline),
             "create the geometry pipeline");
    device.name(pipeline, VK_OBJECT_TYPE_PIPELINE,
                std::string("geometry pipeline ") + (fragment ? fragment : vertex) + " [" + key.text() + "]");
    return PipelineOwner(device.vk(), pipeline);
}

}  // namespace

Result<GeometryPass> GeometryPass::create(const Device& device, VkPipelineLayout layout) {
    GeometryPass pass;
    Result<RenderPassOwner> rp = createRenderPass(device);
    if (!rp) return rp.error();
    pass.renderPass_ = std::move(rp.value());
    // The vertex shader reads no specialization constant: one depth pipeline serves every key.
    Result<PipelineOwner> depthOnly =
        createPipeline(device, layout, pass.renderPass_.get(), SpecKey{}, "geometry.vert", nullptr, true);
    if (!depthOnly) return depthOnly.error();
    pass.depthPipeline_ = std::move(depthOnly.value());
    return pass;
}

namespace {

// The shading pipelines' key: only the constants these shaders read, so that the editor's coarse and
// full frames, whose keys differ in the froxel passes' constants, share their pipelines (a new set of
// surface lights builds one).
SpecKey geometryKey(const SpecKey& sceneKey, bool shapes) {
    return shapes ? constantsReadBy(sceneKey, {"geometry_shapes.frag", "geometry_sphere_shapes.frag"})
                  : constantsReadBy(sceneKey, {"geometry.frag", "geometry_sphere.frag"});
}

const char* shadingVertex(bool sphere) { return sphere ? "geometry_sphere.vert" : "geometry.vert"; }

const char* shadingFragment(bool shapes, bool sphere) {
    return sphere ? (shapes ? "geometry_sphere_shapes.frag" : "geometry_sphere.frag")
                  : (shapes ? "geometry_shapes.frag" : "geometry.frag");
}

}  // namespace

void GeometryPass::request(const Device& device, VkPipelineLayout layout, const SpecKey& sceneKey, bool shapes,
                           bool spheres, PipelineBatch& batch) {
    const SpecKey key = geometryKey(sceneKey, shapes);
    for (bool sphere : {false, true}) {
        if (sphere && !spheres) break;
        auto [it, added] = pipelines_.emplace(std::tuple{key, shapes, sphere}, PipelineOwner{});
        if (!added) continue;  // made, or requested by a batch that failed: usePipeline reports why
        // The entry's address stays put while the batch runs (std::map), and only this job writes it.
        PipelineOwner* out = &it->second;
        const VkRenderPass renderPass = renderPass_.get();
        batch.add(
            [&device, layout, renderPass, key, shapes, sphere, out]() -> Result<void> {
                Result<PipelineOwner> p = createPipeline(device, layout, renderPass, key, shadingVertex(sphere),
                                                         shadingFragment(shapes, sphere), false);
                if (!p) return p.error();
                *out = std::move(p.value());
                return {};
            },
            embeddedSpirv(shadingVertex(sphere)).size() + embeddedSpirv(shadingFragment(shapes, sphere)).size());
    }
}

bool GeometryPass::has(const SpecKey& sceneKey, bool shapes, bool spheres) const {
    const SpecKey key = geometryKey(sceneKey, shapes);
    for (bool sphere : {false, true}) {
        if (sphere && !spheres) break;
        const auto it = pipelines_.find(std::tuple{key, shapes, sphere});
        if (it == pipelines_.end() || !it->second) return false;
    }
    return !spheres || sphereDepthPipeline_;
}

Result<void> GeometryPass::usePipeline(const Device& device, VkPipelineLayout layout, const SpecKey& sceneKey,
                                       bool shapes, bool spheres) {
    const SpecKey key = geometryKey(sceneKey, shapes);
    auto shading = [&](bool sphere) -> Result<VkPipeline> {
        PipelineOwner& slot = pipelines_[{key, shapes, sphere}];
        if (!slot) {
            Result<PipelineOwner> pipeline = createPipeline(device, layout, renderPass_.get(), key, shadingVertex(sphere),
                                                            shadingFragment(shapes, sphere), false);
            if (!pipeline) return pipeline.error();
            slot = std::move(pipeline.value());
        }
        return slot.get();
    };
    Result<VkPipeline> triangles = shading(false);
    if (!triangles) return triangles.error();
    pipeline_ = triangles.value();
    spherePipeline_ = VK_NULL_HANDLE;
    if (!spheres) return {};
    if (!sphereDepthPipeline_) {
        // The sphere's depth does not depend on the key: one depth pipeline serves every frame.
        Result<PipelineOwner> depth = createPipeline(device, layout, renderPass_.get(), SpecKey{},
                                                     "geometry_sphere_depth.vert", "geometry_sphere_depth.frag", true,
                                                     /*attributes=*/2);
        if (!depth) return depth.error();
        sphereDepthPipeline_ = std::move(depth.value());
    }
    Result<VkPipeline> sphere = shading(true);
    if (!sphere) return sphere.error();
    spherePipeline_ = sphere.value();
    return {};
}

Result<void> GeometryPass::attach(const Device& device, const FrameResources& r) {
    framebuffer_ = FramebufferOwner{};
    depthBuffer_ = GpuImage{};
    const VkExtent3D e{static_cast<uint32_t>(r.size.x), static_cast<uint32_t>(r.size.y), 1};
    Result<GpuImage> depth = createImage(device, e, false, VK_FORMAT_D32_SFLOAT,
                                         VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, "geometry depth buffer");
    if (!depth) return depth.error();
    depthBuffer_ = std::move(depth.value());
    const std::array<VkImageView, 3> views{r[ImageId::sceneColor].view.get(), r[ImageId::sceneDepth].view.get(),
                                           depthBuffer_.view.get()};
    VkFramebufferCreateInfo info = vkStruct<VkFramebufferCreateInfo>(VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO);
    info.renderPass = renderPass_.get();
    info.attachmentCount = static_cast<uint32_t>(views.size());
    info.pAttachments = views.data();
    info.width = static_cast<uint32_t>(r.size.x);
    info.height = static_cast<uint32_t>(r.size.y);
    info.layers = 1;
    VkFramebuffer fb = VK_NULL_HANDLE;
    BRUME_VK(vkCreateFramebuffer(device.vk(), &info, nullptr, &fb), "create the geometry framebuffer");
    framebuffer_ = FramebufferOwner(device.vk(), fb);
    device.name(fb, VK_OBJECT_TYPE_FRAMEBUFFER, "geometry framebuffer");
    return {};
}

void GeometryPass::record(const PassContext& ctx) const {
    const VkCommandBuffer cmd = ctx.cmd;
    const FrameResources& r = *ctx.res;
    const DescriptorBindings& b = *ctx.bindings;
    const uint32_t triangles = ctx.triangleVertices, spheres = ctx.sphereVertices;
    const glm::vec3 ambient = ctx.ambient;
    const float cameraFar = ctx.cameraFar;
    const VkExtent2D extent{static_cast<uint32_t>(r.size.x), static_cast<uint32_t>(r.size.y)};
    std::array<VkClearValue, 3> clears{};
    clears[0].color = {{ambient.r, ambient.g, ambient.b, 1.0f}};  // sky radiance
    clears[1].color = {{cameraFar, 0.0f, 0.0f, 0.0f}};            // sky view depth
    clears[2].depthStencil = {1.0f, 0};
    VkRenderPassBeginInfo begin = vkStruct<VkRenderPassBeginInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO);
    begin.renderPass = renderPass_.get();
    begin.framebuffer = framebuffer_.get();
    begin.renderArea = {{0, 0}, extent};
    begin.clearValueCount = static_cast<uint32_t>(clears.size());
    begin.pClearValues = clears.data();
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    if (triangles + spheres > 0) {
        // clipFromView already flips y for Vulkan's framebuffer, so the viewport is the plain one.
        const VkViewport viewport{0.0f, 0.0f, static_cast<float>(extent.width), static_cast<float>(extent.height),
                                  0.0f, 1.0f};
        const VkRect2D scissor{{0, 0}, extent};
        vkCmdSetViewport(cmd, 0, 1, &viewport);
        vkCmdSetScissor(cmd, 0, 1, &scissor);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, b.pipelineLayout.get(), 0, 1, &b.set, 0,
                                nullptr);
        const VkDeviceSize offset = 0;
        const VkBuffer vb = r.vertices.buffer.get();
        vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &offset);
        // Depth first, then shading where the depth is equal: each visible pixel is shaded once,
        // whatever the draw order (the ground under the wall was shaded, then painted over). The
        // sphere proxies write their ray cast's depth in both, computed alike (geometry.frag).
        auto draw = [&](VkPipeline pipeline, uint32_t count, uint32_t first) {
            if (count == 0) return;
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
            vkCmdDraw(cmd, count, 1, first, 0);
        };
        draw(depthPipeline_.get(), triangles, 0);
        draw(sphereDepthPipeline_.get(), spheres, triangles);
        draw(pipeline_, triangles, 0);
        draw(spherePipeline_, spheres, triangles);
    }
    vkCmdEndRenderPass(cmd);
}

}  // namespace brume::gpu
