#pragma once

#include <vector>

/// The screen-space caustic filter kernels (docs/METHOD.md §7.3),
/// computed on the CPU so tests can check them and the filter shader reads them as they are.
namespace luxel::lighting {

enum class CausticKernel {
    /// Larsen's c(x,y) = s * sum t(x+i, y+j) * sqrt(1 + 2k^2 - (i^2 + j^2)), i, j in [-k, k]:
    /// every tap of the square is positive (the corners weigh 1, the centre sqrt(1 + 2k^2)).
    Larsen,
    /// The (2k+1)^2 box.
    Box,
    /// The round cone 1 - r/d with r = sqrt(i^2 + j^2) and d = k + 1, so every tap within the
    /// disc of radius k is positive and the square's corners (r > k + 1 for k >= 3) drop out.
    RoundCone,
    /// World-space cone: the cone's radius is fixed in metres (CausticPassSettings::
    /// world_radius) and converted to pixels per pixel from its depth; neighbours whose depth
    /// differs from the centre's by more than that radius do not contribute, so a caustic does
    /// not bleed across a depth edge. Its weights are computed in the shader.
    WorldCone,
    /// Level-adjusted mip-maps (S. Larsen 2006): per pixel the finest level of the splat
    /// buffer's mip chain whose block holds CausticPassSettings::mip_min_photons photons, so
    /// the kernel widens where photons are sparse (close-ups) and narrows where they are dense.
    /// Computed in the shader (shaders/caustics/mip_filter.comp); no fixed weights. Beside a
    /// small, very bright focus every widened pixel takes in the focus's power again (cornell's
    /// sphere: far brighter than the reference, docs/RESULTS.md "Close-ups"): not the default.
    MipLevels,
    /// Ray-differential footprints (S. Larsen 2006 §4.4.5; docs/METHOD.md §7.4): each photon
    /// spread over the disc its photon differential says it stands for (CausticPhoton::
    /// footprint), with an Epanechnikov kernel normalised on that disc, so it keeps its power
    /// however wide it is drawn; at least CausticPassSettings::footprint_min_pixels pixels and
    /// at most world_radius. Drawn per photon, not filtered per pixel: no fixed weights.
    PhotonFootprints,
};

[[nodiscard]] const char* kernel_name(CausticKernel kernel);

/// The (2k+1)^2 weights of a screen-space kernel, row-major (index (j + k) * (2k + 1) + i + k),
/// normalised to sum 1 (the s of Larsen's formula): a photon splatted away from the screen
/// border keeps its power through the filter. Throws luxel::Error for WorldCone (no fixed
/// weights) or k outside [0, kMaxCausticKernelRadius].
[[nodiscard]] std::vector<float> caustic_kernel_weights(CausticKernel kernel, int k);

/// The largest kernel radius in pixels: the filter stages a (16 + 2k)^2 block of the splat
/// buffer in shared memory, which must stay below the 32 KiB every GL 4.5 driver provides.
inline constexpr int kMaxCausticKernelRadius = 8;

}  // namespace luxel::lighting
