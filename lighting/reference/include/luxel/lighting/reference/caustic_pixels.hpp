#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/reference/caustic_footprints.hpp"
#include "luxel/lighting/reference/caustic_reference.hpp"
#include "luxel/lighting/reference/reference_frame.hpp"
#include "luxel/lighting/reference/reference_scene.hpp"
#include "luxel/runtime/image.hpp"

/// The caustic a camera sees, at pixel resolution (docs/METHOD.md §10.1): each pixel's centre
/// ray, where it meets a diffuse surface directly, gives a footprint (CausticFootprints) the size
/// of the patch the pixel covers there, and the pixel shows albedo / pi times the caustic
/// irradiance over it. Close to a caustic this is the reference a screen-space or texel method
/// must be judged by; ReferenceFrame's caustics are light-map texels, blocky close up.
namespace luxel::lighting::reference {

struct CausticPixels {
    int width = 0;
    int height = 0;
    /// Per pixel (rows top first): its footprint, or -1 where the centre ray meets no diffuse
    /// front face first (the sky, glass, a mirror, a back face).
    std::vector<std::int64_t> footprint_of_pixel;
    std::vector<CausticFootprint> footprints;
    std::vector<glm::vec3> albedo;  ///< per footprint: the diffuse albedo at its centre
};

/// The footprints of `camera`'s pixels in `scene`. The pixel's solid angle is measured from the
/// rays through its edges' midpoints; throws luxel::Error for a camera whose pixels have none
/// (orthographic).
[[nodiscard]] CausticPixels caustic_pixels(const ReferenceScene& scene,
                                           const ReferenceCamera& camera);

/// The caustic radiance each pixel shows, W/(m^2 sr): albedo / pi times the caustic irradiance
/// over its footprint (`caustics` must have been given `pixels.footprints`, in that order);
/// 0 where the pixel has no footprint. Alpha 1 where it has one, 0 where not: the pixels the
/// estimate covers, for an error measured over them alone.
[[nodiscard]] Image caustic_pixel_image(const CausticPixels& pixels,
                                        const CausticReference& caustics);

/// The image's own expected relRMSE over the pixels with a footprint: sqrt(sum se^2 / sum
/// mean^2) over them and the channels (0 where they hold no caustic).
[[nodiscard]] double caustic_pixels_relative_standard_error(const CausticPixels& pixels,
                                                            const CausticReference& caustics);

}  // namespace luxel::lighting::reference
