#pragma once

// Reference frames for luxel-bench's image error (docs/METHOD.md §10.2): the level's camera path
// traced by ReferenceFrame as luxel-ref renders it, cached on disk beside the light-map
// references.

#include <filesystem>
#include <string>

#include "bench_options.hpp"
#include "luxel/lighting/reference/reference_frame.hpp"
#include "luxel/lighting/reference/reference_scene.hpp"
#include "luxel/runtime/image.hpp"
#include "luxel/runtime/jobs.hpp"

namespace luxel::bench {

struct ReferenceImage {
    std::string key;   ///< level, pose, camera, size, spp, caustic photons, seed
    std::string hash;  ///< the cache files' name
    Image image;       ///< linear radiance W/(m^2 sr), rows top first
    /// The frame's own expected image relRMSE (ReferenceFrame::relative_standard_error).
    double relative_standard_error = 0.0;
    /// The caustic term alone at pixel resolution (caustic_pixel_image: alpha 1 on the pixels
    /// that see a diffuse surface directly), from the same caustic photons, and its expected
    /// relRMSE over those pixels.
    Image caustic_pixels;
    double caustic_pixels_se = 0.0;
    double seconds = 0.0;  ///< to compute it
    bool from_cache = false;
};

/// The camera's matrices and size as text, for cache keys.
[[nodiscard]] std::string describe_camera(const lighting::reference::ReferenceCamera& camera);

/// The reference frame of `camera` in the pose `pose` (as for reference_for): read from
/// `cache_dir`/<hash>.frame.json + .frame.exr when present and matching, else computed (the
/// caustic photons of spec.caustic_photons for the diffuse surfaces' delta-light caustics, then
/// image.spp path samples per pixel, in four passes as luxel-ref does) and written there.
[[nodiscard]] ReferenceImage reference_image_for(const std::filesystem::path& cache_dir,
                                                 const std::string& pose,
                                                 const lighting::reference::ReferenceScene& scene,
                                                 const lighting::reference::ReferenceCamera& camera,
                                                 const ReferenceSpec& spec, const ImageSpec& image,
                                                 JobSystem& jobs);

/// The image error with the reference's own noise taken out: a reference pixel's noise adds
/// its variance to both sums of relRMSE^2 = sum (x - r)^2 / sum r^2 in expectation, so with
/// s = the reference's relative standard error the estimate is sqrt((e^2 - s^2) / (1 - s^2))
/// (0 when the noise explains all of e; +infinity when s >= 1 leaves nothing to judge by).
[[nodiscard]] double net_of_reference_noise(double relrmse, double reference_se);

/// Writes the real-time frame (left) and the reference (right) side by side as one PNG, both
/// tone-mapped with one exposure metered on the reference. Throws luxel::Error if the sizes
/// differ or the file cannot be written.
void write_side_by_side(const std::filesystem::path& path, const Image& real_time,
                        const Image& reference);

}  // namespace luxel::bench
