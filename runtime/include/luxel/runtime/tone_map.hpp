#pragma once

#include <glm/glm.hpp>

namespace luxel {

/// How linear HDR radiance becomes a displayable [0,1] value before sRGB encoding. Tone mapping
/// is for display and PNG only; measurements always use the linear frame (EXR).
enum class ToneMapOperator {
    Clamp,     ///< exposure, then clamp to [0,1]: exact for values already in range
    Reinhard,  ///< x / (1 + x) per channel
    Aces,      ///< Narkowicz's fit of the ACES filmic curve
};

struct ToneMapSettings {
    ToneMapOperator op = ToneMapOperator::Aces;
    float exposure = 1.0f;  ///< linear multiplier applied before the curve
};

/// IEC 61966-2-1 transfer functions on [0,1].
[[nodiscard]] float linear_to_srgb(float linear);
[[nodiscard]] float srgb_to_linear(float encoded);

/// The luminance of linear RGB (Rec. 709 / sRGB primaries): what the eye weighs a colour by,
/// for meters, light picks and difference pictures.
[[nodiscard]] inline double luminance(const glm::dvec3& rgb) {
    return 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b;
}

/// Maps linear radiance to display-linear [0,1] (not yet sRGB-encoded). NaN maps to 0.
[[nodiscard]] glm::vec3 tone_map(const glm::vec3& linear, const ToneMapSettings& settings);

}  // namespace luxel
