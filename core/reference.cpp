// The CPU reference: one ray per pixel centre, marched front to back with adaptive midpoint steps
// and the exact slab formula per step. Deliberately simple; docs/reference.md states the model and
// its measured error bound. Ray parameters are doubles so that steps of 1e-9 m still advance a ray
// that is 1e6 m long.
#include <algorithm>
#include <cstdint>
#include <cmath>
#include <limits>
#include <vector>

#include "geometry.h"
#include "parallel.h"
#include "progress.h"
#include "reference_detail.h"
#include "render.h"

namespace brume::reference {

using shd::BRUME_HUGE;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

bool isUnbounded(double length) { return length >= 0.5 * static_cast<double>(BRUME_HUGE); }

float maxComponent(glm::vec3 v) { return std::max(v.x, std::max(v.y, v.z)); }

glm::dvec3 transformPoint(const glm::mat4& m, glm::dvec3 p) { return glm::dvec3(glm::dmat4(m) * glm::dvec4(p, 1.0)); }
glm::dvec3 transformDir(const glm::mat4& m, glm::dvec3 d) { return glm::dvec3(glm::dmat4(m) * glm::dvec4(d, 0.0)); }

Interval intersect(Interval a, double lo, double hi) { return Interval{std::max(a.t0, lo), std::min(a.t1, hi)}; }

// Box-kind volumes: the unit cube, ball or cylinder in local space, and the inner shape where a
// faded one has density 1. Affine maps keep the ray parameter, so local intervals are world intervals.
Interval ballIntervalD(glm::dvec3 o, glm::dvec3 d, double r) {
    const double a = glm::dot(d, d), b = glm::dot(o, d), c = glm::dot(o, o) - r * r;
    const double disc = b * b - a * c;
    if (!(a > 0.0) || !(disc >= 0.0)) return Interval{};
    const double root = std::sqrt(disc);
    return Interval{(-b - root) / a, (-b + root) / a};
}

Interval boxInterval(const shd::VolumeData& v, glm::dvec3 o, glm::dvec3 d, double half) {
    const glm::dvec3 lo = transformPoint(v.localFromWorld, o), ld = transformDir(v.localFromWorld, d);
    if (shd::boxShape(v) == shd::SHAPE_ELLIPSOID) return ballIntervalD(lo, ld, half);
    if (shd::boxShape(v) == shd::SHAPE_CYLINDER) {
        const Interval slab = rayBoxInterval(lo, ld, glm::dvec3(-kInf, -half, -kInf), glm::dvec3(kInf, half, kInf));
        const bool axial = ld.x == 0.0 && ld.z == 0.0;
        const Interval disc = axial ? (lo.x * lo.x + lo.z * lo.z <= half * half ? Interval{-kInf, kInf} : Interval{})
                                    : ballIntervalD(glm::dvec3(lo.x, 0.0, lo.z), glm::dvec3(ld.x, 0.0, ld.z), half);
        return Interval{std::max(slab.t0, disc.t0), std::min(slab.t1, disc.t1)};
    }
    return rayBoxInterval(lo, ld, glm::dvec3(-half), glm::dvec3(half));
}

double innerHalf(const shd::VolumeData& v) { return 0.5 * (1.0 - static_cast<double>(v.params.x)); }

bool hasFade(const shd::VolumeData& v) { return v.params.x > 0.0f; }

// Midpoint rule for a density along origin + s * dir, s in [a, b].
template <class DensityFn>
double marchDensity(DensityFn density, glm::dvec3 o, glm::dvec3 d, double a, double b, int n) {
    const double h = (b - a) / n;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) sum += density(glm::vec3(o + d * (a + (i + 0.5) * h)));
    return sum * h;
}

double smoothstepD(double e0, double e1, double u) {
    const double x = std::clamp((u - e0) / (e1 - e0), 0.0, 1.0);
    return x * x * (3.0 - 2.0 * x);
}

// Integral of smoothstep(e0, e1, u) over u from below e0 (where it is 0).
double smoothstepIntegral(double e0, double e1, double u) {
    if (u <= e0) return 0.0;
    const double w = e1 - e0;
    if (u >= e1) return 0.5 * w + (u - e1);
    const double x = (u - e0) / w;
    return w * x * x * x * (1.0 - 0.5 * x);
}

// Box density is 1 - smoothstep(1 - fade, 1, u) with u = 2 max|q_a| in local coordinates. Along a
// line each q_a is linear, so u is linear between the parameters where two |q_a| cross: split there
// and integrate the smoothstep exactly, in closed form.
// Ellipsoids, cylinders and height-falling boxes: the midpoint rule on the chord's pieces outside,
// inside and again outside the inner shape (on each the density is smooth), 64 steps a piece.
double shapeDensityIntegral(const shd::VolumeData& v, glm::dvec3 o, glm::dvec3 d, Interval chord) {
    Interval inner = intersect(boxInterval(v, o, d, innerHalf(v)), chord.t0, chord.t1);
    if (!(inner.t1 > inner.t0)) inner = Interval{chord.t0, chord.t0};
    auto density = [&](glm::vec3 p) { return static_cast<double>(shd::boxDensity(v, p)); };
    return marchDensity(density, o, d, chord.t0, inner.t0, 64) + marchDensity(density, o, d, inner.t0, inner.t1, 64) +
           marchDensity(density, o, d, inner.t1, chord.t1, 64);
}

double boxDensityIntegral(const shd::VolumeData& v, glm::dvec3 o, glm::dvec3 d, double length) {
    const Interval chord = intersect(boxInterval(v, o, d, 0.5), 0.0, length);
    if (chord.empty()) return 0.0;
    if (shd::boxShape(v) != shd::SHAPE_BOX || v.params.z > 0.0f) return shapeDensityIntegral(v, o, d, chord);
    if (!hasFade(v)) return chord.t1 - chord.t0;
    const glm::dvec3 lo = transformPoint(v.localFromWorld, o), ld = transformDir(v.localFromWorld, d);
    double cuts[8];
    int n = 0;
    cuts[n++] = chord.t0;
    for (int a = 0; a < 3; ++a)
        for (int b = a + 1; b < 3; ++b)
            for (double sign : {-1.0, 1.0}) {
                const double denom = ld[a] - sign * ld[b];
                if (denom == 0.0) continue;
                const double s = (sign * lo[b] - lo[a]) / denom;
                if (s > chord.t0 && s < chord.t1) cuts[n++] = s;
            }
    cuts[n++] = chord.t1;
    for (int i = 1; i < n; ++i)  // insertion sort: at most 8 entries
        for (int j = i; j > 0 && cuts[j - 1] > cuts[j]; --j) std::swap(cuts[j - 1], cuts[j]);
    const double e0 = 1.0 - static_cast<double>(v.params.x);
    double total = 0.0;
    for (int i = 0; i + 1 < n; ++i) {
        const double s0 = cuts[i], s1 = cuts[i + 1], len = s1 - s0;
        if (len <= 0.0) continue;
        const glm::dvec3 qm = glm::abs(lo + ld * (0.5 * (s0 + s1)));
        const int a = qm.x >= qm.y && qm.x >= qm.z ? 0 : (qm.y >= qm.z ? 1 : 2);
        const double sign = lo[a] + ld[a] * (0.5 * (s0 + s1)) >= 0.0 ? 2.0 : -2.0;
        const double u0 = sign * (lo[a] + ld[a] * s0), u1 = sign * (lo[a] + ld[a] * s1);
        // u nearly constant (a face-parallel ray): the midpoint value, free of the cancellation.
        const double faded = std::abs(u1 - u0) < 1e-9 * (1.0 + std::abs(u0))
                                 ? smoothstepD(e0, 1.0, 0.5 * (u0 + u1)) * len
                                 : (smoothstepIntegral(e0, 1.0, u1) - smoothstepIntegral(e0, 1.0, u0)) * len / (u1 - u0);
        total += len - faded;
    }
    return total;
}

// Depth fog rises toward density 1 with the distance to the camera: unbounded rays see infinite
// optical depth; bounded ones are marched at a tenth of the visibility distance. (Light toward
// lights ignores depth fog: see fogTransmittance.)
double depthDensityIntegral(const shd::VolumeData& v, glm::vec3 camera, glm::dvec3 o, glm::dvec3 d, double length) {
    if (isUnbounded(length)) return kInf;
    const double vis = static_cast<double>(v.params.x);
    const int n = static_cast<int>(std::clamp(std::ceil(length / (0.1 * vis)), 4.0, 256.0));
    auto density = [&](glm::vec3 p) { return static_cast<double>(shd::depthDensity(v, p, camera)); };
    return marchDensity(density, o, d, 0.0, length, n);
}

// Grids: midpoint rule over the part of the ray inside the grid's bounds, a quarter voxel per step
// (trilinear density is piecewise smooth at that scale), capped so no grid can hang a shadow ray.
double vdbDensityIntegral(const CompiledScene& cs, size_t i, glm::dvec3 o, glm::dvec3 d, double length) {
    const shd::VolumeData& v = cs.volumes[i];
    if (!cs.grids[i]) return 0.0;
    const Interval in = intersect(rayBoxInterval(o, d, glm::dvec3(v.worldMin), glm::dvec3(v.worldMax)), 0.0, length);
    if (in.empty() || !(in.t1 > in.t0)) return 0.0;
    const double step = 0.25 * static_cast<double>(v.params.y);
    const int n = static_cast<int>(std::clamp(std::ceil((in.t1 - in.t0) / step), 1.0, 65536.0));
    // Fog shadows see no density texture in any renderer (docs/vdb.md): the plain grid here too.
    auto density = [&](glm::vec3 p) { return static_cast<double>(plainVolumeDensity(cs, i, p)); };
    return marchDensity(density, o, d, in.t0, in.t1, n);
}

double volumeDensityIntegral(const CompiledScene& cs, size_t i, glm::dvec3 o, glm::dvec3 d, double length) {
    const shd::VolumeData& v = cs.volumes[i];
    switch (v.kind.x) {
        case shd::VOLUME_BOX: return boxDensityIntegral(v, o, d, length);
        case shd::VOLUME_HEIGHT_EXPONENTIAL:
        case shd::VOLUME_HEIGHT_LINEAR: return heightDensityIntegral(v, o, d, length);
        case shd::VOLUME_DEPTH: return depthDensityIntegral(v, cs.cameraPosition, o, d, length);
        case shd::VOLUME_VDB: return vdbDensityIntegral(cs, i, o, d, length);
        default: return 0.0;
    }
}

// Integral of a height profile's density over heights u = y - base in [u0, u1] (u0 <= u1).
double heightProfileIntegral(const shd::VolumeData& v, double u0, double u1) {
    const double below = std::max(0.0, std::min(u1, 0.0) - u0);
    const double a = std::max(u0, 0.0), b = std::max(u1, 0.0);
    const double p = static_cast<double>(v.params.y);
    if (v.kind.x == shd::VOLUME_HEIGHT_LINEAR) {
        if (p <= 0.0) return below;  // a step profile
        const double ac = std::min(a, p), bc = std::min(b, p);
        return below + (bc - ac) * (1.0 - (ac + bc) / (2.0 * p));
    }
    if (p <= 0.0) return below + (b - a);
    // exp(-p a) - exp(-p b) written without cancellation.
    return below + std::exp(-p * a) * -std::expm1(-p * (b - a)) / p;
}

double heightDensityAt(const shd::VolumeData& v, double u) {
    const double p = static_cast<double>(v.params.y);
    if (u <= 0.0) return 1.0;
    if (v.kind.x == shd::VOLUME_HEIGHT_LINEAR) return std::clamp(1.0 - u / p, 0.0, 1.0);
    return std::exp(-p * u);
}

}  // namespace

Interval rayBoxInterval(glm::dvec3 o, glm::dvec3 d, glm::dvec3 lo, glm::dvec3 hi) {
    Interval r{-kInf, kInf};
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0) {
            if (o[a] < lo[a] || o[a] > hi[a]) return Interval{};
            continue;
        }
        double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
        if (ta > tb) std::swap(ta, tb);
        r.t0 = std::max(r.t0, ta);
        r.t1 = std::min(r.t1, tb);
    }
    return r;
}

double heightDensityIntegral(const shd::VolumeData& v, glm::dvec3 o, glm::dvec3 d, double length) {
    const double u0 = o.y - static_cast<double>(v.params.x);
    const double dy = d.y;
    if (isUnbounded(length)) {
        // Downward or level rays below the top stay in density > 0 forever.
        if (dy <= 0.0) return heightDensityAt(v, u0) > 0.0 || dy < 0.0 ? kInf : 0.0;
        if (v.kind.x == shd::VOLUME_HEIGHT_EXPONENTIAL && v.params.y <= 0.0f) return kInf;
        return heightProfileIntegral(v, u0, kInf) / dy;
    }
    const double du = dy * length;
    // Nearly level segments: the midpoint value is exact to the (tiny) curvature over |du|, and
    // avoids the rounding of u0 + du when |du| << |u0|.
    if (std::abs(du) < 1e-9 * (1.0 + std::abs(u0))) return heightDensityAt(v, u0 + 0.5 * du) * length;
    return heightProfileIntegral(v, std::min(u0, u0 + du), std::max(u0, u0 + du)) / std::abs(dy);
}

glm::vec3 fogTransmittance(const CompiledScene& cs, glm::vec3 from, glm::vec3 dir, float maxDist) {
    glm::dvec3 tau(0.0);
    const glm::dvec3 o(from), d(dir);
    for (size_t i = 0; i < cs.volumes.size(); ++i) {
        const shd::VolumeData& v = cs.volumes[i];
        // Depth fog is aerial perspective: its density is measured from the camera and fills all
        // space, so as an occluder it would put out every light and move shadows with the camera.
        // It dims what the camera sees, never the light on its way to a point (docs/scene-format.md).
        if (v.kind.x == shd::VOLUME_DEPTH) continue;
        const double integral = volumeDensityIntegral(cs, i, o, d, static_cast<double>(maxDist));
        if (!(integral > 0.0)) continue;
        const glm::vec3 sigmaT = glm::vec3(v.sigmaS_g) + glm::vec3(v.sigmaA);
        for (int c = 0; c < 3; ++c)
            if (sigmaT[c] > 0.0f) tau[c] += std::isinf(integral) ? kInf : static_cast<double>(sigmaT[c]) * integral;
    }
    return glm::vec3(glm::exp(-tau));
}


namespace {

struct CameraRay {
    glm::dvec3 origin;
    glm::dvec3 dir;  // unit
    double tEnd;     // first surface hit or the far plane
    SurfaceHit hit;
    double pixelAngle;  // [rad] between this pixel's ray and its neighbours' (the smaller): footprint = t x this
};

// Renders single pixels; shared read-only by the worker threads.
class Tracer {
public:
    Tracer(const Scene& scene, const CompiledScene& cs, const GeometrySet& geo, const shd::FrameUniforms& frame,
           const StepParams& params)
        : scene_(scene), cs_(cs), geo_(geo), frame_(frame), params_(params) {
        for (size_t i = 0; i < cs_.volumes.size(); ++i) {
            const shd::VolumeData& v = cs_.volumes[i];
            glm::vec2 m(1.0f);
            if (i < cs_.textures.size() && cs_.textures[i]) m.x = layerMeanFactor(*cs_.textures[i], v.textureParams, v.textureMin, v.textureSize);
            if (i < cs_.details.size() && cs_.details[i]) m.y = layerMeanFactor(*cs_.details[i], v.detailParams, v.detailMin, v.detailSize);
            textureMeans_.push_back(m);
        }
    }

    glm::vec3 radiance(int x, int y) const {
        const CameraRay ray = cameraRay(x, y);
        shd::Accumulated acc = shd::emptyAccumulated();
        std::vector<double> cuts = breakpoints(ray);
        int steps = 0;
        for (size_t i = 0; i + 1 < cuts.size(); ++i) {
            if (!pieceHasMedia(ray, 0.5 * (cuts[i] + cuts[i + 1]))) continue;
            if (!marchPiece(ray, cuts[i], cuts[i + 1], acc, steps)) break;
        }
        return shd::compositeFog(background(ray), acc);
    }

private:
    CameraRay cameraRay(int x, int y) const {
        const glm::vec3 view = shd::viewRayFromPixel(glm::vec2(float(x) + 0.5f, float(y) + 0.5f), frame_);
        const double viewLen = glm::length(glm::dvec3(view));
        CameraRay r;
        auto angleTo = [&](float px, float py) {
            const glm::dvec3 a(view), b(shd::viewRayFromPixel(glm::vec2(px, py), frame_));
            return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
        };
        r.pixelAngle = std::min(angleTo(float(x) + 1.5f, float(y) + 0.5f), angleTo(float(x) + 0.5f, float(y) + 1.5f));
        r.origin = glm::dvec3(scene_.camera.position);
        r.dir = glm::normalize(glm::dvec3(glm::mat3(frame_.worldFromView) * view));
        const double tFar = static_cast<double>(scene_.camera.far) * viewLen;
        // Surfaces nearer than the near plane are clipped, as the rasterizer clips them.
        const float tNear = static_cast<float>(static_cast<double>(scene_.camera.near) * viewLen);
        r.hit = geo_.intersect(Ray{glm::vec3(r.origin), glm::vec3(r.dir)}, static_cast<float>(tFar), tNear);
        r.tEnd = r.hit.hit() ? static_cast<double>(r.hit.t) : tFar;
        return r;
    }

    glm::vec3 background(const CameraRay& ray) const {
        if (!ray.hit.hit()) return cs_.ambient;
        const LightTransmittanceFn fog = [this](int, glm::vec3 p, glm::vec3 dir, float dist) {
            return fogTransmittance(cs_, p, dir, dist);
        };
        return shadeSurface(cs_, geo_, ray.hit, &fog);
    }

    // Every place along the ray where some density is discontinuous or has a kink that we can find
    // exactly, so that no step straddles one.
    std::vector<double> breakpoints(const CameraRay& ray) const {
        std::vector<double> t{0.0, ray.tEnd};
        auto add = [&](double s) {
            if (s > 0.0 && s < ray.tEnd) t.push_back(s);
        };
        auto addInterval = [&](Interval i) {
            if (!i.empty()) add(i.t0), add(i.t1);
        };
        for (const shd::VolumeData& v : cs_.volumes) {
            addInterval(rayBoxInterval(ray.origin, ray.dir, glm::dvec3(v.worldMin), glm::dvec3(v.worldMax)));
            if (v.kind.x == shd::VOLUME_BOX) {
                addInterval(boxInterval(v, ray.origin, ray.dir, 0.5));
                if (hasFade(v)) addInterval(boxInterval(v, ray.origin, ray.dir, innerHalf(v)));
            } else if (v.kind.x == shd::VOLUME_DEPTH) {
                add(static_cast<double>(v.params.y));  // the ray starts at the camera: distance = t
            } else if (v.kind.x != shd::VOLUME_VDB && ray.dir.y != 0.0) {  // height fog
                add((static_cast<double>(v.params.x) - ray.origin.y) / ray.dir.y);
                if (v.kind.x == shd::VOLUME_HEIGHT_LINEAR)
                    add((static_cast<double>(v.params.x + v.params.y) - ray.origin.y) / ray.dir.y);
            }
        }
        // The influencers' box: a piece inside it starts inside it, where stepLimit resolves the falloff.
        if (cs_.influence.header.count.x > 0)
            addInterval(rayBoxInterval(ray.origin, ray.dir, glm::dvec3(glm::vec3(cs_.influence.header.boundsMin)),
                                       glm::dvec3(glm::vec3(cs_.influence.header.boundsMax))));
        std::sort(t.begin(), t.end());
        t.erase(std::unique(t.begin(), t.end()), t.end());
        return t;
    }

    // Bounds crossings are breakpoints, so a piece is inside a volume's bounds everywhere or nowhere.
    bool pieceHasMedia(const CameraRay& ray, double tMid) const {
        const glm::vec3 p(ray.origin + ray.dir * tMid);
        for (const shd::VolumeData& v : cs_.volumes) {
            if (!shd::insideBounds(v, p)) continue;
            // Depth fog is empty before its start distance (a breakpoint): no steps there.
            if (v.kind.x == shd::VOLUME_DEPTH && tMid < static_cast<double>(v.params.y)) continue;
            if (v.kind.x != shd::VOLUME_BOX || shd::boxDensity(v, p) > 0.0f) return true;
        }
        return false;
    }

    // Returns false once the view transmittance is below the cutoff (or the step cap is reached).
    bool marchPiece(const CameraRay& ray, double a, double b, shd::Accumulated& acc, int& steps) const {
        const double scale = static_cast<double>(params_.step_scale);
        const double pieceStep = scale * (b - a) / params_.min_piece_steps;
        const double tauStep = scale * static_cast<double>(params_.tau_step);
        float sigmaPrev = 0.0f;
        uint32_t maskStart = shadowMask(position(ray, a));
        for (double t = a; t < b;) {
            const double minStep = 1e-12 * (1.0 + t);  // keeps t + h > t in double
            double h = std::max(std::min(pieceStep, scale * stepLimit(ray, t, sigmaPrev)), minStep);
            if (b - t <= h) h = b - t;
            else if (b - t < 2.0 * h) h = 0.5 * (b - t);
            shd::MediaSample mid = stepMedia(ray, t, h);
            // The predicted extinction was too low (denser medium ahead): shrink to match.
            const float sigmaMid = liveSigmaT(mid.sigmaT, acc.transmittance);
            if (static_cast<double>(sigmaMid) * h > 2.0 * tauStep) {
                h = std::max(tauStep / sigmaMid, minStep);
                mid = stepMedia(ray, t, h);
            }
            // A geometry shadow boundary inside the step: the midpoint rule errs by up to the jump
            // times h/2 there, so such steps are split into shadow_substeps.
            const uint32_t maskEnd = shadowMask(position(ray, t + h));
            if (maskEnd == maskStart) {
                sigmaPrev = addStep(ray, t, h, mid, acc);
            } else {
                const int sub = params_.shadow_substeps;
                for (int i = 0; i < sub; ++i) {
                    const double ti = t + h * i / sub;
                    sigmaPrev = addStep(ray, ti, h / sub, stepMedia(ray, ti, h / sub), acc);
                }
            }
            maskStart = maskEnd;
            t += h;
            if (maxComponent(acc.transmittance) < params_.transmittance_cutoff) return false;
            if (++steps >= params_.max_steps) return false;
        }
        return true;
    }

    static glm::vec3 position(const CameraRay& ray, double t) { return glm::vec3(ray.origin + ray.dir * t); }

    // Midpoint-rule step [t, t + h] with the exact slab formula; returns the step's sigma_t limit
    // (liveSigmaT). m: the step's media (stepMedia).
    float addStep(const CameraRay& ray, double t, double h, const shd::MediaSample& m, shd::Accumulated& acc) const {
        const glm::vec3 p = position(ray, t + 0.5 * h);
        const glm::vec3 light = m.sigmaS == glm::vec3(0.0f) ? glm::vec3(0.0f)
                                                            : inScatter(p, glm::vec3(ray.dir), shd::mediaPhaseG(m));
        const glm::vec3 source = m.sigmaS * (light + cs_.ambient) + m.emission;
        acc = shd::accumulateSlab(acc, source, m.sigmaT, static_cast<float>(h));
        return liveSigmaT(m.sigmaT, acc.transmittance);
    }

    // The largest sigma_t among the channels that can still be seen (view transmittance above the
    // cutoff). A channel already put out adds nothing behind it, so its extinction must not hold the
    // step length down: a medium opaque in red only would otherwise take steps of 0.25 / sigma_t
    // across its whole length (2^20 steps per pixel at 1e9/m).
    float liveSigmaT(glm::vec3 sigmaT, glm::vec3 transmittance) const {
        float s = 0.0f;
        for (int c = 0; c < 3; ++c)
            if (transmittance[c] >= params_.transmittance_cutoff) s = std::max(s, sigmaT[c]);
        return s;
    }

    // Media of the step [t, t + h]: every volume's density at the midpoint, except depth fog, whose
    // density along a camera ray (distance from the camera = t) is 1 - exp(-3 (t - start) / vis),
    // taken as its exact mean over the step (closed form), so steps may grow where it saturates.
    shd::MediaSample stepMedia(const CameraRay& ray, double t, double h) const {
        const glm::vec3 p = position(ray, t + 0.5 * h);
        shd::MediaSample m = shd::emptyMedia();
        for (size_t i = 0; i < cs_.volumes.size(); ++i) {
            const shd::VolumeData& v = cs_.volumes[i];
            if (!shd::insideBounds(v, p)) continue;
            const float density = v.kind.x == shd::VOLUME_DEPTH ? static_cast<float>(depthMean(v, t, t + h))
                                                                : plainVolumeDensity(cs_, i, p);
            const double footprint = ray.pixelAngle * (t + 0.5 * h);
            m = shd::addMedium(m, v, density > 0.0f ? density * textureFactorSeen(i, p, footprint) : density);
        }
        // Influencers thin the fog the camera sees, not the fog shadows (fogTransmittance).
        if (shd::insideInfluenceBounds(cs_.influence.header, p)) m = shd::influenceScaleMedia(m, influenceFactor(cs_.influence, p));
        return m;
    }

    // A volume's density texture factor as a pixel sees it at footprint (the pixel's width at p): each
    // layer is sampled where one of its tiles is wider than the footprint, and is its mean over a tile
    // beyond (docs/reference.md "Density textures").
    float textureFactorSeen(size_t i, glm::vec3 p, double footprint) const {
        if (i >= cs_.textures.size() || !cs_.textures[i]) return 1.0f;
        const shd::VolumeData& v = cs_.volumes[i];
        float factor = textureMeans_[i].x;
        if (footprint < tileSize(v.textureParams)) {
            const shd::TextureCell c = shd::textureCell(v, p, cs_.time);
            factor = shd::textureDensityFactor(v, cs_.textures[i]->sampleCorners(c.lo, c.hi, c.frac, v.textureParams.w));
        }
        if (i < cs_.details.size() && cs_.details[i]) {
            float detail = textureMeans_[i].y;
            if (footprint < tileSize(v.detailParams)) {
                const shd::TextureCell c = shd::detailCell(v, p, cs_.time);
                detail = shd::detailDensityFactor(v, cs_.details[i]->sampleCorners(c.lo, c.hi, c.frac, v.detailParams.w));
            }
            factor *= detail;
        }
        return factor;
    }

    // A layer's factor max(0, 1 + strength (value / mean - 1)) averaged over a tile: exactly 1 when
    // no voxel's factor is held at 0 (the trilinear field's extremes are at voxels, and it keeps the
    // voxels' mean); else the voxels' mean of the held factor, an upper bound (the hold is convex).
    static float layerMeanFactor(const DensityGrid& grid, glm::vec4 params, glm::ivec4 boxMin, glm::ivec4 boxSize) {
        if (params.y <= 1.0f) return 1.0f;  // 1 + strength (value / mean - 1) >= 1 - strength >= 0
        double sum = 0.0;
        const glm::ivec3 n(boxSize), o(boxMin);
        for (int k = 0; k < n.z; ++k)
            for (int j = 0; j < n.y; ++j)
                for (int i = 0; i < n.x; ++i) {
                    const glm::ivec3 c = o + glm::ivec3(i, j, k);  // a corner: the voxel's shaped value
                    sum += static_cast<double>(shd::textureLayerFactor(params, grid.sampleCorners(c, c, glm::vec3(0.0f), params.w)));
                }
        return static_cast<float>(sum / (static_cast<double>(n.x) * n.y * n.z));
    }

    static double tileSize(glm::vec4 params) { return 1.0 / static_cast<double>(params.x); }

    // Mean of the depth fog density over camera-ray distances [t0, t1].
    static double depthMean(const shd::VolumeData& v, double t0, double t1) {
        const double start = static_cast<double>(v.params.y), k = 3.0 / static_cast<double>(v.params.x);
        const double a = std::max(t0 - start, 0.0), b = std::max(t1 - start, 0.0);
        if (!(t1 > t0) || !(b > a)) return 0.0;
        // Integral of 1 - exp(-k x) over [a, b], without cancellation.
        const double integral = (b - a) + std::exp(-k * a) * std::expm1(-k * (b - a)) / k;
        return std::clamp(integral / (t1 - t0), 0.0, 1.0);
    }

    // Bit i: light i (of the first 32) lights fog, casts shadows and is occluded by geometry at p.
    uint32_t shadowMask(glm::vec3 p) const {
        uint32_t mask = 0;
        for (size_t i = 0; i < std::min<size_t>(cs_.lights.size(), 32); ++i) {
            const shd::LightData& l = cs_.lights[i];
            if (!shd::lightCastsShadows(l) || l.fogScale <= 0.0f) continue;
            const shd::LightSample s = shd::evalLight(l, p);
            if (geo_.occluded(p, s.toLight, s.distance)) mask |= 1u << i;
        }
        return mask;
    }

    // Unscaled step limit at ray parameter t (see StepParams).
    double stepLimit(const CameraRay& ray, double t, float sigmaPrev) const {
        const glm::vec3 p(ray.origin + ray.dir * t);
        double h = std::max(static_cast<double>(params_.near_step), static_cast<double>(params_.rel_step) * t);
        if (sigmaPrev > 0.0f) h = std::min(h, static_cast<double>(params_.tau_step / sigmaPrev));
        for (const shd::LightData& l : cs_.lights) {
            if (l.kind.x == shd::LIGHT_DIRECTIONAL || l.fogScale <= 0.0f) continue;
            const float dist = std::max(glm::length(glm::vec3(l.positionRange) - p), shd::LIGHT_MIN_DISTANCE);
            h = std::min(h, static_cast<double>(params_.light_step * dist));
        }
        // An influencer's falloff changes over its radius: the smallest radius is the scale in their box.
        if (shd::insideInfluenceBounds(cs_.influence.header, p)) h = std::min(h, static_cast<double>(params_.density_step) * smallestInfluenceRadius());
        for (const shd::VolumeData& v : cs_.volumes) {
            if (!shd::insideBounds(v, p)) continue;
            h = std::min(h, static_cast<double>(params_.density_step) * densityScale(v, ray, p));
            // A density texture's trilinear field changes over one of its voxels, like a grid's, where a
            // voxel is at least a pixel wide (a quarter voxel per step); where it is narrower the steps
            // grow as footprint^2 / (4 voxel) to one footprint (each midpoint samples the texture, an
            // estimate of its average over the footprint, which is what the pixel sees), and where a
            // whole tile is narrower the layer is its mean (textureFactorSeen): no limit.
            const double footprint = ray.pixelAngle * t, ds = static_cast<double>(params_.density_step);
            auto layer = [&](glm::vec4 texParams, glm::ivec4 size) {
                const double voxel = textureVoxel(texParams, size);
                if (footprint < tileSize(texParams))
                    h = std::min(h, std::max(ds * voxel, std::min(footprint, ds * footprint * footprint / voxel)));
            };
            if (shd::hasDensityTexture(v)) layer(v.textureParams, v.textureSize);
            if (shd::hasDetailTexture(v)) layer(v.detailParams, v.detailSize);
        }
        return h;
    }

    double smallestInfluenceRadius() const {
        double r = kInf;
        for (const shd::InfluenceSample& s : cs_.influence.samples) r = std::min(r, static_cast<double>(s.a.w));
        return r;
    }

    // World edge of a density texture layer's voxel: a tile holds boxSize voxels per axis.
    static double textureVoxel(glm::vec4 params, glm::ivec4 boxSize) {
        const glm::ivec3 n(boxSize);
        return 1.0 / (static_cast<double>(params.x) * static_cast<double>(std::max({n.x, n.y, n.z})));
    }

    // Ray length over which a volume's density changes by about a factor e (or its fade width).
    double densityScale(const shd::VolumeData& v, const CameraRay& ray, glm::vec3 p) const {
        if (v.kind.x == shd::VOLUME_HEIGHT_EXPONENTIAL && p.y > v.params.x && v.params.y > 0.0f)
            return 1.0 / (static_cast<double>(v.params.y) * std::max(std::abs(ray.dir.y), 1e-30));
        if (v.kind.x == shd::VOLUME_DEPTH) {
            // The length over which the density changes by about 1 (vis/3 at the start), growing as
            // the density saturates: the steps through the ramp stay few (about 1/density_step),
            // whatever the visibility distance, and none are spent where the density is constant.
            const double vis = static_cast<double>(v.params.x);
            const double x = static_cast<double>(glm::length(p - cs_.cameraPosition) - v.params.y);
            if (x < 0.0) return kInf;  // before the start: no density
            return vis / 3.0 * std::exp(std::min(3.0 * x / vis, 700.0));
        }
        // Trilinear density changes over a voxel: a voxel edge is its scale (density_step of it per step).
        // height_falloff: a factor e over 1 / (falloff |dir.y|).
        if (v.kind.x == shd::VOLUME_VDB)
            return v.params.z > 0.0f ? std::min(static_cast<double>(v.params.y),
                                                1.0 / (static_cast<double>(v.params.z) * std::max(std::abs(ray.dir.y), 1e-30)))
                                     : static_cast<double>(v.params.y);
        if (v.kind.x == shd::VOLUME_BOX) {
            // height_falloff: a factor e over 1 / (falloff |dir.y|).
            const double height = v.params.z > 0.0f ? 1.0 / (static_cast<double>(v.params.z) * std::max(std::abs(ray.dir.y), 1e-30))
                                                    : kInf;
            const glm::vec3 q = glm::vec3(v.localFromWorld * glm::vec4(p, 1.0f));
            if (!hasFade(v) || shd::shapeDistance(shd::boxShape(v), 2.0f * q) < 1.0f - v.params.x) return height;
            const double speed = glm::length(transformDir(v.localFromWorld, ray.dir));
            return std::min(height, 0.5 * static_cast<double>(v.params.x) / std::max(speed, 1e-30));
        }
        return kInf;
    }

    // Light scattered toward the camera at p per unit sigma_s, from every light, with geometry
    // shadows (lights with shadows on) and the fog transmittance toward the light.
    glm::vec3 inScatter(glm::vec3 p, glm::vec3 viewDir, float g) const {
        glm::vec3 sum(0.0f);
        for (const shd::LightData& l : cs_.lights) {
            if (l.fogScale <= 0.0f) continue;
            const shd::LightSample s = shd::evalLight(l, p);
            if (maxComponent(s.irradiance) <= 0.0f) continue;
            if (shd::lightCastsShadows(l) && geo_.occluded(p, s.toLight, s.distance)) continue;
            sum += shd::inScatterPerSigmaS(l, s, viewDir, g) * fogTransmittance(cs_, p, s.toLight, s.distance);
        }
        return sum;
    }

    const Scene& scene_;
    const CompiledScene& cs_;
    const GeometrySet& geo_;
    const shd::FrameUniforms& frame_;
    const StepParams& params_;
    std::vector<glm::vec2> textureMeans_;  // per volume: its texture's and detail's mean factor over a tile
};

}  // namespace

Image render(const Scene& scene, const RenderRequest& request, const StepParams& params) {
    if (request.width <= 0 || request.height <= 0) return Image();
    const CompiledScene cs = compileScene(scene);
    const GeometrySet geo(scene.geometry);
    const FroxelSettings fs = resolveFroxelSettings(scene, request.quality);
    const shd::FrameUniforms frame = makeFrameUniforms(scene, cs, request.width, request.height, fs);
    const Tracer tracer(scene, cs, geo, frame, params);
    Image img(request.width, request.height);
    const int rows = request.height;
    ProgressReporter progress(request.progress, rows);
    // Rows skipped after a cancel are not progress.
    auto done = [&](int finished) {
        if (!request.cancel || !request.cancel->load(std::memory_order_relaxed)) progress.report(finished);
    };
    parallelFor(
        rows, request.threads,
        [&](int y) {
            if (request.cancel && request.cancel->load(std::memory_order_relaxed)) return;
            for (int x = 0; x < request.width; ++x) img.at(x, y) = tracer.radiance(x, y);
        },
        done);
    return img;
}

}  // namespace brume::reference

namespace brume {

Image renderReference(const Scene& scene, const RenderRequest& request) {
    return reference::render(scene, request, reference::StepParams{});
}

}  // namespace brume
