// Debug view pass (shaders/debug_view.comp; reads and writes in frame_table.cpp).
#include "passes.h"

namespace brume::gpu {

// One invocation per pixel; the view and slice travel as push constants (the layout's one range).
void recordDebugView(const PassContext& ctx) {
    vkCmdBindPipeline(ctx.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, ctx.pipeline->pipeline.get());
    vkCmdPushConstants(ctx.cmd, ctx.bindings->pipelineLayout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0,
                       sizeof(ctx.debugParams), &ctx.debugParams);
    dispatchPass(ctx);
}

}  // namespace brume::gpu
