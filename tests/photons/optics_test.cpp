// Reflection, refraction and Fresnel reflectance against analytic values; radiance and
// absorption across and inside a closed solid.

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "luxel/lighting/core/halton.hpp"
#include "luxel/lighting/core/optics.hpp"
#include "luxel/lighting/core/photon_tracer.hpp"

namespace {

using namespace luxel::lighting;

glm::vec3 incoming(float degrees) {
    // In the xy plane, arriving at `degrees` from the normal +y, travelling downwards.
    const float a = glm::radians(degrees);
    return {std::sin(a), -std::cos(a), 0.0f};
}

TEST(Optics, ReflectionMirrorsAboutTheNormal) {
    const glm::vec3 n(0, 1, 0);
    for (float degrees : {0.0f, 45.0f, 80.0f}) {
        const glm::vec3 r = optics::reflect(incoming(degrees), n);
        EXPECT_NEAR(r.x, std::sin(glm::radians(degrees)), 1e-6f);
        EXPECT_NEAR(r.y, std::cos(glm::radians(degrees)), 1e-6f);
    }
}

TEST(Optics, RefractionFollowsSnellsLaw) {
    const glm::vec3 n(0, 1, 0);
    for (float degrees : {0.0f, 45.0f, 80.0f}) {
        const auto t = optics::refract(incoming(degrees), n, 1.0f, 1.5f);
        ASSERT_TRUE(t.has_value());
        const float sin_t = std::sin(glm::radians(degrees)) / 1.5f;
        EXPECT_NEAR(t->x, sin_t, 1e-6f);
        EXPECT_NEAR(t->y, -std::sqrt(1.0f - sin_t * sin_t), 1e-6f);
        EXPECT_NEAR(glm::length(*t), 1.0f, 1e-6f);
    }
    // Glass to air: the critical angle is asin(1 / 1.5) = 41.81 degrees.
    EXPECT_TRUE(optics::refract(incoming(41.0f), n, 1.5f, 1.0f).has_value());
    EXPECT_FALSE(optics::refract(incoming(42.0f), n, 1.5f, 1.0f).has_value());
    EXPECT_FALSE(optics::refract(incoming(80.0f), n, 1.5f, 1.0f).has_value());
}

TEST(Optics, FresnelMatchesAnalyticValues) {
    // Normal incidence: ((n1 - n2) / (n1 + n2))^2 = 0.04 for air to glass.
    EXPECT_NEAR(optics::fresnel_dielectric(1.0f, 1.0f, 1.5f), 0.04f, 1e-6f);
    // 45 degrees, air to glass: Rs = 0.0920, Rp = 0.0085 (from the Fresnel equations), mean
    // 0.0503.
    EXPECT_NEAR(optics::fresnel_dielectric(std::cos(glm::radians(45.0f)), 1.0f, 1.5f), 0.0503f,
                2e-4f);
    // 80 degrees: Rs = 0.6133, Rp = 0.3009 (Rs and Rp computed independently below).
    auto reference = [](float degrees, float n1, float n2) {
        const double i = glm::radians(double(degrees));
        const double t = std::asin(n1 / n2 * std::sin(i));
        const double rs = std::pow(std::sin(i - t) / std::sin(i + t), 2.0);
        const double rp = std::pow(std::tan(i - t) / std::tan(i + t), 2.0);
        return 0.5 * (rs + rp);
    };
    for (float degrees : {10.0f, 45.0f, 80.0f}) {
        EXPECT_NEAR(optics::fresnel_dielectric(std::cos(glm::radians(degrees)), 1.0f, 1.5f),
                    reference(degrees, 1.0f, 1.5f), 1e-5)
            << degrees;
        EXPECT_NEAR(optics::fresnel_dielectric(std::cos(glm::radians(degrees * 0.4f)), 1.5f, 1.0f),
                    reference(degrees * 0.4f, 1.5f, 1.0f), 1e-5)
            << degrees;
    }
    // Beyond the critical angle everything reflects.
    EXPECT_EQ(optics::fresnel_dielectric(std::cos(glm::radians(45.0f)), 1.5f, 1.0f), 1.0f);
    // Grazing incidence reflects (almost) everything.
    EXPECT_NEAR(optics::fresnel_dielectric(0.0f, 1.0f, 1.33f), 1.0f, 1e-6f);
}

TEST(Optics, ConductorFresnelRisesToOneAtGrazing) {
    const glm::vec3 brass(0.91f, 0.78f, 0.42f);
    const glm::vec3 normal = optics::fresnel_conductor(1.0f, brass);
    EXPECT_NEAR(normal.b, 0.42f, 1e-6f);
    const glm::vec3 grazing = optics::fresnel_conductor(0.0f, brass);
    EXPECT_NEAR(grazing.b, 1.0f, 1e-6f);
}

/// A hit on a plane y = 0 whose front faces +y, `distance` from where the ray left.
RayHit plane_hit(float distance) {
    RayHit hit;
    hit.distance = distance;
    hit.geometric_normal = glm::vec3(0.0f, 1.0f, 0.0f);
    hit.shading_normal = hit.geometric_normal;
    return hit;
}

TEST(Optics, ADielectricsInsideAbsorbsOnTheWayOutOnly) {
    TraceMaterial glass;
    glass.scattering = Scattering::Dielectric;
    glass.ior = 1.5f;
    glass.tint = glm::vec3(0.9f, 0.8f, 1.0f);
    glass.attenuation_color = glm::vec3(0.25f, 0.5f, 1.0f);
    glass.attenuation_distance = 0.5f;
    // xi = 0.99 refracts (the reflectance at normal incidence is 0.04).
    const auto scatter = [&](const glm::vec3& direction, float distance) {
        const RayHit hit = plane_hit(distance);
        glm::vec3 origin(0.0f);
        glm::vec3 d = direction;
        glm::vec3 power(1.0f);
        scatter_specular(glass, hit, facing_normals(hit, d), 0.99, origin, d, power);
        return power;
    };
    // Entering (arriving on the front): the tint alone, however far the ray came through air.
    const glm::vec3 entering = scatter(glm::vec3(0.0f, -1.0f, 0.0f), 3.0f);
    EXPECT_NEAR(entering.r, 0.9f, 1e-6f);
    EXPECT_NEAR(entering.g, 0.8f, 1e-6f);
    EXPECT_NEAR(entering.b, 1.0f, 1e-6f);
    // Leaving after 1 m inside (twice the attenuation distance): colour^2, then the tint.
    const glm::vec3 leaving = scatter(glm::vec3(0.0f, 1.0f, 0.0f), 1.0f);
    EXPECT_NEAR(leaving.r, 0.0625f * 0.9f, 1e-6f);
    EXPECT_NEAR(leaving.g, 0.25f * 0.8f, 1e-6f);
    EXPECT_NEAR(leaving.b, 1.0f, 1e-6f);
    // Clear glass (the default) absorbs nothing on the way out.
    glass.attenuation_distance = std::numeric_limits<float>::infinity();
    EXPECT_NEAR(scatter(glm::vec3(0.0f, 1.0f, 0.0f), 1.0f).r, 0.9f, 1e-6f);
}

TEST(Optics, RadianceScalesByTheIndicesSquaredAcrossAClosedSolidsFaceOnly) {
    TraceMaterial glass;
    glass.scattering = Scattering::Dielectric;
    glass.ior = 1.5f;
    glass.closed = true;
    // Into the solid 1 / 2.25, out of it 2.25: through both faces the factors cancel.
    EXPECT_NEAR(refracted_radiance_scale(glass, true), 1.0f / 2.25f, 1e-6f);
    EXPECT_NEAR(refracted_radiance_scale(glass, false), 2.25f, 1e-6f);
    EXPECT_NEAR(refracted_radiance_scale(glass, true) * refracted_radiance_scale(glass, false),
                1.0f, 1e-6f);
    // An open sheet (a pane as one quad, a water surface), a mirror, a diffuse surface and a
    // broken index scale nothing.
    TraceMaterial sheet = glass;
    sheet.closed = false;
    EXPECT_EQ(refracted_radiance_scale(sheet, false), 1.0f);
    TraceMaterial mirror = glass;
    mirror.scattering = Scattering::Mirror;
    EXPECT_EQ(refracted_radiance_scale(mirror, true), 1.0f);
    EXPECT_EQ(refracted_radiance_scale(TraceMaterial{}, true), 1.0f);
    for (const float ior : {0.0f, -1.5f, std::numeric_limits<float>::quiet_NaN(),
                            std::numeric_limits<float>::infinity()}) {
        TraceMaterial broken = glass;
        broken.ior = ior;
        EXPECT_EQ(refracted_radiance_scale(broken, false), 1.0f) << ior;
    }
}

TEST(Optics, AClosedSolidAbsorbsOnTheWayToADiffuseSurfaceInsideIt) {
    TraceMaterial glass;
    glass.scattering = Scattering::Dielectric;
    glass.closed = true;
    glass.attenuation_color = glm::vec3(0.25f, 0.5f, 1.0f);
    glass.attenuation_distance = 0.5f;
    const auto absorbed = [](const ClosedMedium& medium, float distance) {
        glm::vec3 power(1.0f);
        medium.absorb(distance, power);
        return power;
    };
    ClosedMedium medium;
    EXPECT_EQ(absorbed(medium, 1.0f), glm::vec3(1.0f));  // in the air
    medium.update(glass, true, false);                   // reflected off its outside
    EXPECT_FALSE(medium.inside());
    medium.update(glass, true, true);  // refracted in through the front
    ASSERT_TRUE(medium.inside());
    // 1 m inside, twice the attenuation distance: the colour squared.
    const glm::vec3 kept = absorbed(medium, 1.0f);
    EXPECT_NEAR(kept.r, 0.0625f, 1e-6f);
    EXPECT_NEAR(kept.g, 0.25f, 1e-6f);
    EXPECT_NEAR(kept.b, 1.0f, 1e-6f);
    medium.update(glass, false, true);  // out through the back
    EXPECT_FALSE(medium.inside());
    // A path that starts inside (a floor under the block) learns it at the first back face:
    // reflected there (total internal reflection), it is still inside.
    ClosedMedium from_inside;
    from_inside.update(glass, false, false);
    EXPECT_TRUE(from_inside.inside());
    EXPECT_NEAR(absorbed(from_inside, 0.5f).r, 0.25f, 1e-6f);
    // An open sheet has no inside: nothing changes, nothing is absorbed.
    TraceMaterial sheet = glass;
    sheet.closed = false;
    ClosedMedium past_sheet;
    past_sheet.update(sheet, true, true);
    EXPECT_FALSE(past_sheet.inside());
    EXPECT_EQ(absorbed(past_sheet, 1.0f), glm::vec3(1.0f));
    // Clear glass absorbs nothing, inside or not.
    TraceMaterial clear = glass;
    clear.attenuation_distance = std::numeric_limits<float>::infinity();
    ClosedMedium in_clear;
    in_clear.update(clear, true, true);
    EXPECT_TRUE(in_clear.inside());
    EXPECT_EQ(absorbed(in_clear, 10.0f), glm::vec3(1.0f));
}

TEST(Halton, RadicalInverseDigitsAndStratification) {
    EXPECT_DOUBLE_EQ(radical_inverse(2, 1), 0.5);
    EXPECT_DOUBLE_EQ(radical_inverse(2, 6), 0.375);      // 110b -> 0.011b
    EXPECT_DOUBLE_EQ(radical_inverse(3, 5), 7.0 / 9.0);  // 12_3 -> 0.21_3
    // The first 2^k points of base 2 fall one in each interval of width 2^-k.
    std::vector<int> cells(64, 0);
    for (std::uint64_t i = 0; i < 64; ++i) {
        cells[static_cast<std::size_t>(radical_inverse(2, i) * 64.0)] += 1;
    }
    for (int count : cells) {
        EXPECT_EQ(count, 1);
    }
}

/// Phi_b(i) exactly: the digits of i reversed into a numerator over b^k by long division,
/// independently of the library's code (b^k < 2^40 for the indices below 2^32 it is used for).
struct ExactRadicalInverse {
    std::uint64_t numerator = 0;
    std::uint64_t denominator = 1;
};
ExactRadicalInverse exact_radical_inverse(std::uint32_t base, std::uint64_t index) {
    ExactRadicalInverse exact;
    for (; index > 0; index /= base) {
        exact.numerator = exact.numerator * base + index % base;
        exact.denominator *= base;
    }
    return exact;
}

TEST(Halton, RadicalInverseIsTheCorrectlyRoundedQuotientInEveryPhotonDimension) {
    std::vector<std::uint64_t> indices;
    for (std::uint64_t i = 0; i < 3000; ++i) {
        indices.push_back(i);
    }
    for (std::uint64_t i = 1; i < 64; ++i) {  // scattered up to 2^32 - 1
        indices.push_back((i * 0x9E3779B97F4A7C15ull) >> 32);
    }
    indices.push_back(0xFFFFFFFFull);
    for (std::uint32_t dim = 0; dim < kHaltonPrimes.size(); ++dim) {
        const std::uint32_t base = kHaltonPrimes[dim];
        for (const std::uint64_t index : indices) {
            const ExactRadicalInverse exact = exact_radical_inverse(base, index);
            // Below 2^32, numerator and b^k fit 53 bits: their double quotient is the value
            // correctly rounded.
            ASSERT_LT(exact.denominator, std::uint64_t{1} << 53);
            const double expected =
                static_cast<double>(exact.numerator) / static_cast<double>(exact.denominator);
            const double value = radical_inverse_in_dimension(dim, index);
            ASSERT_EQ(value, expected) << "base " << base << ", index " << index;
            ASSERT_EQ(radical_inverse(base, index), expected);
            ASSERT_GE(value, 0.0);
            ASSERT_LT(value, 1.0);
            // The sum of rounded terms (the definition) agrees to rounding.
            ASSERT_NEAR(radical_inverse_sum(base, index), expected, 1e-15);
        }
    }
}

TEST(Halton, RadicalInverseOfLargeIndices) {
    // Base 2 reverses bits, exact to 2^53; other bases fall back to the sum past 2^32.
    for (const std::uint64_t index :
         {std::uint64_t{1} << 32, (std::uint64_t{1} << 40) + 12345, (std::uint64_t{1} << 53) - 1}) {
        EXPECT_EQ(radical_inverse_in_dimension(0, index), radical_inverse_sum(2, index));
        for (std::uint32_t dim = 1; dim < kHaltonPrimes.size(); ++dim) {
            const double value = radical_inverse_in_dimension(dim, index);
            EXPECT_EQ(value, radical_inverse_sum(kHaltonPrimes[dim], index));
            EXPECT_GE(value, 0.0);
            EXPECT_LT(value, 1.0);
        }
    }
    // No digits in base 0 or 1: zero, not an endless loop or a division by zero.
    EXPECT_EQ(radical_inverse(0, 17), 0.0);
    EXPECT_EQ(radical_inverse(1, 17), 0.0);
}

}  // namespace
