// Helpers shared by the GPU test binaries: a validated renderer per test, froxel volumes as images.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "core/image.h"
#include "gpu/gpu_renderer.h"

namespace brume::test {

// A froxel volume (one vec4 per froxel, as FroxelVolumes holds them) as a one-row image, so that
// relativeMeanAbsError compares GPU and CPU volumes like images.
inline Image asImage(const std::vector<glm::vec4>& v) {
    Image img(static_cast<int>(v.size()), 1);
    for (size_t i = 0; i < v.size(); ++i) img.pixels[i] = glm::vec3(v[i]);
    return img;
}

// A fresh renderer with the validation layer on for every test; any message it reports fails the
// test. Fixtures that set up more call ValidatedGpuTest::SetUp() first and stop on HasFatalFailure().
class ValidatedGpuTest : public ::testing::Test {
protected:
    void SetUp() override {
        gpu::GpuOptions options;
        options.validation = true;
        auto r = gpu::GpuRenderer::create(options);
        ASSERT_TRUE(r.ok()) << r.error().message;
        renderer = std::move(r.value());
    }
    void TearDown() override {
        if (!renderer) return;
        const std::vector<std::string> messages = renderer->validationMessages();
        EXPECT_TRUE(messages.empty()) << messages.size() << " validation messages, first: " << messages.front();
    }

    std::unique_ptr<gpu::GpuRenderer> renderer;
};

}  // namespace brume::test
