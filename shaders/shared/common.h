// Thin language layer so that one header compiles as C++ (with GLM) and as GLSL 4.50.
// Rules for code in shaders/shared/: no references, no out-parameters (return structs), no
// constructors with braces, float literals with an f suffix, every function defined before use and
// declared with BRUME_FUNC (inline in C++, so the header can be included by many translation units).
#ifndef BRUME_SHARED_COMMON_H
#define BRUME_SHARED_COMMON_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
#define BRUME_NAMESPACE_BEGIN \
    namespace brume::shd {    \
    using namespace glm;      \
    using uint = std::uint32_t;
#define BRUME_NAMESPACE_END }
#define BRUME_CONST inline constexpr
#define BRUME_FUNC inline
#else
#define BRUME_NAMESPACE_BEGIN
#define BRUME_NAMESPACE_END
#define BRUME_CONST const
#define BRUME_FUNC
#endif

BRUME_NAMESPACE_BEGIN

BRUME_CONST float BRUME_PI = 3.14159265358979f;
BRUME_CONST float BRUME_INV_4PI = 0.0795774715459477f;
// Stands for "unbounded" in world-space bounds; finite so that min/max arithmetic never makes NaN.
BRUME_CONST float BRUME_HUGE = 1.0e30f;

BRUME_NAMESPACE_END

#endif
