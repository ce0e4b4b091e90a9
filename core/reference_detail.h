// Internals of the CPU reference renderer (core/reference.cpp), exposed so that tests can check the
// closed forms and the convergence of the step control. docs/reference.md defines the model.
#pragma once

#include <glm/glm.hpp>

#include "compile.h"
#include "image.h"
#include "render.h"
#include "scene.h"

namespace brume::reference {

// Step control of the camera-ray march. Every step is at most
//   min(max(near_step, rel_step * t), tau_step / sigma_t, light_step * distance to the nearest
//       point/spot light, density_step * the length over which a volume's density changes),
// each piece between breakpoints takes at least min_piece_steps steps, and every limit is scaled
// by step_scale (0.5 halves every step; the convergence test compares the two).
struct StepParams {
    float step_scale = 1.0f;
    float near_step = 0.05f;       // [m]
    float rel_step = 0.01f;        // fraction of the distance from the camera
    float tau_step = 0.25f;        // optical depth per step
    float light_step = 0.2f;       // fraction of the distance to a point/spot light
    float density_step = 0.25f;    // fraction of a density falloff length
    int min_piece_steps = 8;
    // Steps across which a geometry shadow toward some light begins or ends are split this many times.
    int shadow_substeps = 16;
    // The march stops once every channel of the view transmittance is below this: what lies behind
    // contributes at most this fraction of its radiance.
    float transmittance_cutoff = 1.0e-6f;
    // Hard cap so that no input can hang a render (never reached on valid scenes).
    int max_steps = 1 << 20;
};

// [t0, t1] along a ray; empty when t0 > t1.
struct Interval {
    double t0 = 1.0;
    double t1 = 0.0;
    bool empty() const { return t0 > t1; }
};

// Parameter interval of origin + t * dir inside the axis-aligned box [lo, hi] (dir need not be unit).
Interval rayBoxInterval(glm::dvec3 origin, glm::dvec3 dir, glm::dvec3 lo, glm::dvec3 hi);

// Integral of a height volume's density along origin + s * dir (dir unit), s in [0, length]
// (length >= BRUME_HUGE means unbounded), in closed form. Infinite when the integral diverges.
double heightDensityIntegral(const shd::VolumeData& v, glm::dvec3 origin, glm::dvec3 dir, double length);

// Fog transmittance from `from` along unit `dir` over `maxDist` (>= BRUME_HUGE: to infinity, the sun)
// through every volume: closed forms for boxes (hard or faded) and height fog, a midpoint march for
// depth fog.
glm::vec3 fogTransmittance(const CompiledScene& cs, glm::vec3 from, glm::vec3 dir, float maxDist);

Image render(const Scene& scene, const RenderRequest& request, const StepParams& params);

}  // namespace brume::reference
