#include "luxel/lighting/core/spherical_harmonics.hpp"

#include <glm/gtc/constants.hpp>

namespace luxel::lighting {

ShBasis sh_basis(const glm::vec3& d) {
    // The normalisation constants of the real harmonics: sqrt(1/4pi), sqrt(3/4pi),
    // sqrt(15/4pi), sqrt(5/16pi), sqrt(15/16pi).
    constexpr float k0 = 0.282094792f;
    constexpr float k1 = 0.488602512f;
    constexpr float k2 = 1.092548431f;
    constexpr float k20 = 0.315391565f;
    constexpr float k22 = 0.546274215f;
    return {k0,
            k1 * d.y,
            k1 * d.z,
            k1 * d.x,
            k2 * d.x * d.y,
            k2 * d.y * d.z,
            k20 * (3.0f * d.z * d.z - 1.0f),
            k2 * d.x * d.z,
            k22 * (d.x * d.x - d.y * d.y)};
}

ShRgb convolve_cosine(const ShRgb& radiance) {
    constexpr float a0 = glm::pi<float>();
    constexpr float a1 = 2.0f * glm::pi<float>() / 3.0f;
    constexpr float a2 = glm::pi<float>() / 4.0f;
    constexpr std::array<float, kShCoefficients> band{a0, a1, a1, a1, a2, a2, a2, a2, a2};
    ShRgb result;
    for (std::size_t i = 0; i < kShCoefficients; ++i) {
        result.c[i] = radiance.c[i] * band[i];
    }
    return result;
}

glm::vec3 evaluate(const ShRgb& coefficients, const glm::vec3& n) {
    const ShBasis y = sh_basis(n);
    glm::vec3 sum(0.0f);
    for (std::size_t i = 0; i < kShCoefficients; ++i) {
        sum += coefficients.c[i] * y[i];
    }
    return glm::max(sum, glm::vec3(0.0f));
}

}  // namespace luxel::lighting
