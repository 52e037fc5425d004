#include "luxel/runtime/tone_map.hpp"

#include <algorithm>
#include <cmath>

namespace luxel {

float linear_to_srgb(float linear) {
    const float x = std::clamp(linear, 0.0f, 1.0f);
    return x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
}

float srgb_to_linear(float encoded) {
    const float x = std::clamp(encoded, 0.0f, 1.0f);
    return x <= 0.04045f ? x / 12.92f : std::pow((x + 0.055f) / 1.055f, 2.4f);
}

namespace {

float curve(float x, ToneMapOperator op) {
    if (!(x > 0.0f)) {  // also catches NaN
        return 0.0f;
    }
    if (std::isinf(x)) {  // every curve saturates; the rational fits would give inf/inf
        return 1.0f;
    }
    switch (op) {
        case ToneMapOperator::Clamp:
            return std::min(x, 1.0f);
        case ToneMapOperator::Reinhard:
            return x / (1.0f + x);
        case ToneMapOperator::Aces: {
            // Narkowicz 2015, a rational fit to the ACES reference rendering transform.
            const float mapped = (x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f);
            return std::clamp(mapped, 0.0f, 1.0f);
        }
    }
    return 0.0f;
}

}  // namespace

glm::vec3 tone_map(const glm::vec3& linear, const ToneMapSettings& settings) {
    const glm::vec3 exposed = linear * settings.exposure;
    return {curve(exposed.r, settings.op), curve(exposed.g, settings.op),
            curve(exposed.b, settings.op)};
}

}  // namespace luxel
