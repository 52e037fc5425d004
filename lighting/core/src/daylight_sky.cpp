#include <algorithm>
#include <array>
#include <cmath>

#include <glm/gtc/constants.hpp>

#include "luxel/lighting/core/sky_radiance.hpp"
#include "luxel/runtime/tone_map.hpp"

// Preetham, Shirley and Smits (1999), appendix A.2: the Perez coefficients of luminance Y and
// chromaticity x, y as linear functions of turbidity, and the zenith's values as functions of
// turbidity and the sun's zenith angle. Written from the paper's formulas.
namespace luxel::lighting {
namespace {

constexpr double kPi = glm::pi<double>();

struct Perez {
    double a, b, c, d, e;
};

/// The Perez function F(theta, gamma) for a view at zenith angle theta and angle gamma from
/// the sun. cos(theta) is kept off zero: the model is not meant for the horizon itself.
double perez(const Perez& p, double cos_theta, double gamma) {
    const double cos_gamma = std::cos(gamma);
    return (1.0 + p.a * std::exp(p.b / std::max(cos_theta, 0.01))) *
           (1.0 + p.c * std::exp(p.d * gamma) + p.e * cos_gamma * cos_gamma);
}

/// The zenith chromaticity: t^2, t, 1 rows against the sun's zenith angle's cube to 1.
double zenith_chromaticity(const std::array<std::array<double, 4>, 3>& m, double t,
                           double theta_sun) {
    const std::array<double, 4> powers{theta_sun * theta_sun * theta_sun, theta_sun * theta_sun,
                                       theta_sun, 1.0};
    const std::array<double, 3> turbidity{t * t, t, 1.0};
    double sum = 0.0;
    for (int row = 0; row < 3; ++row) {
        for (int col = 0; col < 4; ++col) {
            sum += turbidity[static_cast<std::size_t>(row)] *
                   m[static_cast<std::size_t>(row)][static_cast<std::size_t>(col)] *
                   powers[static_cast<std::size_t>(col)];
        }
    }
    return sum;
}

glm::dvec3 xyY_to_linear_srgb(double x, double y, double luminance) {
    if (!(y > 0.0)) {
        return glm::dvec3(0.0);
    }
    const double big_x = x * luminance / y;
    const double big_z = (1.0 - x - y) * luminance / y;
    return {3.2406 * big_x - 1.5372 * luminance - 0.4986 * big_z,
            -0.9689 * big_x + 1.8758 * luminance + 0.0415 * big_z,
            0.0557 * big_x - 0.2040 * luminance + 1.0570 * big_z};
}

}  // namespace

SkyRadiance daylight_sky(const glm::vec3& towards_sun, float turbidity,
                         float horizontal_irradiance) {
    const double t =
        std::isfinite(turbidity) ? std::clamp(static_cast<double>(turbidity), 1.7, 10.0) : 3.0;
    glm::dvec3 sun(towards_sun);
    const double length = glm::length(sun);
    sun = length > 0.0 && std::isfinite(length) ? sun / length : glm::dvec3(0.0, 1.0, 0.0);
    // A sun under the horizon is taken at it (the model ends there; dusk is not modelled).
    if (sun.y < 0.0) {
        sun.y = 0.0;
        const double horizontal = glm::length(sun);
        sun = horizontal > 0.0 ? sun / horizontal : glm::dvec3(1.0, 0.0, 0.0);
    }
    const double theta_sun = std::acos(std::clamp(sun.y, -1.0, 1.0));

    const Perez luminance{0.1787 * t - 1.4630, -0.3554 * t + 0.4275, -0.0227 * t + 5.3251,
                          0.1206 * t - 2.5771, -0.0670 * t + 0.3703};
    const Perez chroma_x{-0.0193 * t - 0.2592, -0.0665 * t + 0.0008, -0.0004 * t + 0.2125,
                         -0.0641 * t - 0.8989, -0.0033 * t + 0.0452};
    const Perez chroma_y{-0.0167 * t - 0.2608, -0.0950 * t + 0.0092, -0.0079 * t + 0.2102,
                         -0.0441 * t - 1.6537, -0.0109 * t + 0.0529};
    const double chi = (4.0 / 9.0 - t / 120.0) * (kPi - 2.0 * theta_sun);
    const double zenith_luminance = (4.0453 * t - 4.9710) * std::tan(chi) - 0.2155 * t + 2.4192;
    const double zenith_x = zenith_chromaticity({{{0.00166, -0.00375, 0.00209, 0.0},
                                                  {-0.02903, 0.06377, -0.03202, 0.00394},
                                                  {0.11693, -0.21196, 0.06052, 0.25886}}},
                                                t, theta_sun);
    const double zenith_y = zenith_chromaticity({{{0.00275, -0.00610, 0.00317, 0.0},
                                                  {-0.04214, 0.08970, -0.04153, 0.00516},
                                                  {0.15346, -0.26756, 0.06670, 0.26688}}},
                                                t, theta_sun);
    const double f0_luminance = perez(luminance, 1.0, theta_sun);
    const double f0_x = perez(chroma_x, 1.0, theta_sun);
    const double f0_y = perez(chroma_y, 1.0, theta_sun);

    constexpr int kWidth = 128;
    constexpr int kHeight = 64;
    std::vector<glm::vec3> cells(static_cast<std::size_t>(kWidth) * kHeight, glm::vec3(0.0f));
    for (int row = 0; row < kHeight / 2; ++row) {  // the upper hemisphere's rows
        const double theta = kPi * (row + 0.5) / kHeight;
        const double cos_theta = std::cos(theta);
        for (int col = 0; col < kWidth; ++col) {
            const double phi = 2.0 * kPi * (col + 0.5) / kWidth;
            const glm::dvec3 view(std::sin(theta) * std::cos(phi), cos_theta,
                                  std::sin(theta) * std::sin(phi));
            const double gamma = std::acos(std::clamp(glm::dot(view, sun), -1.0, 1.0));
            const double y_value =
                zenith_luminance * perez(luminance, cos_theta, gamma) / f0_luminance;
            const double x_chroma = zenith_x * perez(chroma_x, cos_theta, gamma) / f0_x;
            const double y_chroma = zenith_y * perez(chroma_y, cos_theta, gamma) / f0_y;
            cells[static_cast<std::size_t>(row) * kWidth + static_cast<std::size_t>(col)] =
                glm::vec3(
                    glm::max(xyY_to_linear_srgb(x_chroma, y_chroma, y_value), glm::dvec3(0.0)));
        }
    }
    // Scaled so that the irradiance's luminance on an upward face is the one asked for, by the
    // same exact cell integrals a ground below it uses (horizontal_irradiance).
    const glm::dvec3 horizontal =
        lighting::horizontal_irradiance(SkyRadiance(kWidth, kHeight, cells));
    const double luminance_now = luxel::luminance(horizontal);
    const double wanted = std::isfinite(horizontal_irradiance)
                              ? std::max(static_cast<double>(horizontal_irradiance), 0.0)
                              : 0.0;
    const double scale =
        luminance_now > 0.0 && std::isfinite(luminance_now) ? wanted / luminance_now : 0.0;
    for (glm::vec3& cell : cells) {
        cell = glm::vec3(glm::dvec3(cell) * scale);
    }
    return SkyRadiance(kWidth, kHeight, std::move(cells));
}

}  // namespace luxel::lighting
