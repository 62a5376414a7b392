#pragma once
// Mirror reflection, Snell refraction and Fresnel's reflectance of a
// dielectric boundary, in the form the source documents give:
// `incident` points toward the surface, `normal` is unit length and faces the
// side the incident ray comes from (dot(incident, normal) <= 0).
#include <cmath>
#include <optional>

#include "core/Vec3.h"

namespace raycache {

// r = i + 2 n cos(θi), cos(θi) = -(i·n)
inline Vec3 reflect(const Vec3& incident, const Vec3& normal) {
    const float cosI = -dot(incident, normal);
    return incident + normal * (2.0f * cosI);
}

// t = η i + (η cos(θi) - sqrt(cos²θt)) n with cos²θt = 1 - η²(1 - cos²θi) and
// η = η1/η2. Returns nothing on total internal reflection (cos²θt < 0).
inline std::optional<Vec3> refract(const Vec3& incident, const Vec3& normal, float eta) {
    const float cosI = -dot(incident, normal);
    const float cos2T = 1.0f - eta * eta * (1.0f - cosI * cosI);
    if (cos2T < 0.0f) return std::nullopt;
    return incident * eta + normal * (eta * cosI - std::sqrt(cos2T));
}

// Fresnel's reflectances of a smooth boundary between two dielectrics, for
// light polarised perpendicular (s) and parallel (p) to the plane of
// incidence, from cos(θi) and cos(θt) (as refract() finds it: cos²θt =
// 1 - η²(1 - cos²θi)) and η = η1/η2:
//   rs = (η cosθi - cosθt) / (η cosθi + cosθt),  rp = (η cosθt - cosθi) / (η cosθt + cosθi),
// each squared. Both are 1 at grazing incidence, rp is 0 at Brewster's
// angle, and the same pair results from the other side (θt, 1/η).
struct FresnelReflectance {
    float s, p;
    float unpolarised() const { return 0.5f * (s + p); }
};

inline FresnelReflectance dielectricFresnel(float cosI, float cosT, float eta) {
    const float a = eta * cosI;
    const float rs = (a - cosT) / (a + cosT);
    const float b = eta * cosT;
    const float rp = (b - cosI) / (b + cosI);
    return {rs * rs, rp * rp};
}

}  // namespace raycache
