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
// test. Its integrated scattering is NaN before each frame (GpuOptions::poisonIntegrated),
// so an image that reads an entry the integrate pass did not store is not finite and fails its
// test. Fixtures that set up more call ValidatedGpuTest::SetUp() first and stop on HasFatalFailure().
class ValidatedGpuTest : public ::testing::Test {
protected:
    void SetUp() override {
        gpu::GpuOptions options;
        options.validation = true;
        options.poisonIntegrated = true;
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

// The shadow volume region tests' pair: a renderer over the froxel regions whose fog transmittance
// volume is filled with NaN before every frame (GpuOptions::poisonShadowVolume), so that reading a
// cell not written this frame shows, and its S and sigma_t filled with 1 in frames that read no
// volumes back (GpuOptions::poisonSource); and one over the whole grid; both validated. Stops the
// test on an error (check HasFatalFailure()).
struct PoisonedRegionAndWholeGrid {
    std::unique_ptr<gpu::GpuRenderer> region, whole;

    void create() {
        gpu::GpuOptions options;
        options.validation = true;
        options.poisonShadowVolume = true;
        options.poisonSource = true;
        auto r = gpu::GpuRenderer::create(options);
        ASSERT_TRUE(r.ok()) << r.error().message;
        region = std::move(r.value());
        options.froxelRegions = false;
        options.poisonShadowVolume = false;
        options.poisonSource = false;
        auto w = gpu::GpuRenderer::create(options);
        ASSERT_TRUE(w.ok()) << w.error().message;
        whole = std::move(w.value());
    }
    void expectNoValidationMessages() const {
        for (const gpu::GpuRenderer* r : {region.get(), whole.get()}) {
            const std::vector<std::string> messages = r->validationMessages();
            EXPECT_TRUE(messages.empty()) << messages.size() << " validation messages, first: " << messages.front();
        }
    }
};

}  // namespace brume::test
