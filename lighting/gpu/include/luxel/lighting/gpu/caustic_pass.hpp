#pragma once

#include <cstdint>
#include <memory>
#include <span>

#include <glm/glm.hpp>

#include "luxel/lighting/core/caustic_photons.hpp"
#include "luxel/lighting/core/photon_world.hpp"
#include "luxel/lighting/gpu/caustic_kernel.hpp"
#include "luxel/runtime/gl.hpp"

namespace luxel {
class ShaderLibrary;
}

namespace luxel::lighting {

class CausticPhotonBuffer;

/// How the filter finds the pixels to filter.
enum class CausticTileMode {
    Full,      ///< every tile of the viewport, photons or not (the reference)
    EarlyOut,  ///< one work group per tile; groups with no marked tile in reach return at once
    Indirect,  ///< a compute pass compacts the tiles to filter; an indirect dispatch runs those
};

struct CausticPassSettings {
    CausticKernel kernel = CausticKernel::Larsen;
    /// k: the screen-space kernel spans (2k + 1)^2 pixels (the paper: 3). For WorldCone, the
    /// largest radius in pixels a world radius may reach (nearer surfaces are clamped to it).
    int kernel_radius = 3;
    /// WorldCone: the cone's radius in metres. MipLevels and PhotonFootprints: the widest radius in
    /// metres an estimate may reach (as a photon map's largest search radius).
    float world_radius = 0.05f;
    /// PhotonFootprints only: the footprint radius is scaled by this (1: the patch the photon
    /// differential spans among one generation's photons), then held to at least
    /// footprint_min_pixels pixels at the photon's depth (a disc of one pixel's radius always
    /// holds a pixel centre, so its power is kept on average over where it lands) and at most
    /// world_radius. 2 and 1 had the lowest caustic error overall on the caustics level's
    /// four close-up cameras of the grid measured (docs/RESULTS.md, "Close-ups"; luxel-bench
    /// --sweep footprint_scale / footprint_min): a still caustic's refinements add photons the
    /// differential does not know of, and close up noise costs more than blur.
    float footprint_scale = 2.0f;
    float footprint_min_pixels = 1.0f;
    /// PhotonFootprints only: no disc wider than this many pixels in radius, whatever its
    /// footprint or world_radius say. A camera right on a caustic would otherwise draw every
    /// photon over thousands of pixels (a frame's cost follows the discs' area); a capped disc
    /// still keeps its power, it is only noisier. 64: wider than any disc the measured
    /// close-ups drew (5 cm at 0.8 m is about 7 pixels at 160 x 120, 60 at 1920 x 1080).
    float footprint_max_pixels = 64.0f;
    /// MipLevels only: the photons a pixel's estimate needs; the level whose block holds them
    /// is read (relative noise about 1 / sqrt of it).
    float mip_min_photons = 16.0f;
    CausticTileMode tile_mode = CausticTileMode::Indirect;
    /// Divide each photon's power by the pixel's area on the surface (orientation from the
    /// depth buffer's slope: a pixel on a surface seen at angle theta covers 1 / cos(theta)
    /// times the area it covers on a camera-facing one). Off: the camera-facing area
    /// (2 z tan(fov/2) / height)^2 (docs/METHOD.md §7.4), which overestimates irradiance on
    /// oblique surfaces by 1 / cos(theta).
    bool account_for_orientation = true;
    /// The smallest cos(theta) used for the orientation: a grazing pixel's footprint is
    /// unbounded, and a noisy depth slope must not send irradiance to zero.
    float min_cos = 0.05f;
    /// Depth-test tolerance: a photon passes where its view depth is at most the scene's at
    /// its pixel plus relative * depth + absolute (metres) + the surface's depth change across
    /// one pixel (photons anywhere in a pixel of a steep surface still pass).
    float depth_bias_relative = 1e-3f;
    float depth_bias_absolute = 1e-3f;
};

/// The camera of a frame. Perspective projections only (the pixel area and the depth
/// linearisation assume one); vertical field of view and aspect come from `projection`.
struct CausticCamera {
    glm::mat4 view{1.0f};
    glm::mat4 projection{1.0f};
    glm::ivec2 viewport{0};
    /// Depth texture values map to NDC z as d (glClipControl GL_ZERO_TO_ONE, also reversed
    /// depth) instead of 2d - 1 (the GL default).
    bool depth_zero_to_one = false;

    /// glm::perspective(vertical_fov, width / height, near, far) with the GL depth range.
    [[nodiscard]] static CausticCamera perspective(const glm::mat4& view, float vertical_fov,
                                                   glm::ivec2 viewport, float near, float far);
};

/// World-space area (m^2) of a pixel on a surface facing the camera at view depth z:
/// (2 z tan(fov/2) / height)^2 for square pixels; from the projection, 4 z^2 / (P00 P11 W H).
[[nodiscard]] double caustic_pixel_area(const CausticCamera& camera, double view_depth);

/// What the last render() did. GPU times come from GL_TIME_ELAPSED queries and counters from
/// a buffer the shaders write; both are read back (a stall) only when stats() is called.
struct CausticPassStats {
    std::uint32_t photons_drawn = 0;     ///< photons in the draw ranges
    std::uint32_t photons_splatted = 0;  ///< of those, in view and passing the depth test
    std::uint32_t tiles_total = 0;       ///< 16 x 16 tiles of the viewport
    std::uint32_t tiles_marked = 0;      ///< tiles that received a photon
    std::uint32_t tiles_filtered = 0;    ///< work groups that ran the filter
    double splat_ms = 0.0;               ///< clears + splat (GPU)
    double filter_ms = 0.0;              ///< tile compaction + filter (GPU)
    std::uint64_t slices_uploaded = 0;   ///< since construction
    std::uint64_t bytes_uploaded = 0;    ///< since construction
};

inline constexpr int kCausticTileSize = 16;

/// The screen-space caustic pass (docs/METHOD.md §7.3-7.5): caustic photons are drawn as
/// GL_POINTS into an RGBA32F splat buffer with additive blending, each adding
/// power / (the world-space area of its pixel), depth-tested in the vertex shader against the
/// caller's scene depth; the splat marks the 16 x 16 tiles it touches, and a compute filter
/// runs on the marked tiles and their neighbours within the kernel's reach.
///
/// Output: irradiance_texture(), RGBA32F, viewport-sized: rgb is the caustic irradiance E in
/// W/m^2 per channel, not radiance; the composition adds L = albedo / pi * E on diffuse
/// surfaces (shaders/caustics/caustic_radiance.glsl). alpha is the filtered photon count per
/// pixel (for noise estimates). Pixels with no photon within the kernel's reach are 0.
///
/// Why RGBA32F for both buffers: RGB32F is neither a required colour-renderable format nor an
/// image format; R11G11B10F has a 6-bit mantissa, so once a pixel holds 64 photons' worth a
/// small photon's addition rounds away and energy is lost; 16F loses it past ~2048.
///
/// GL objects are created at construction (and again only when the viewport size changes,
/// and the photon buffer when an upload outgrows it); an empty upload allocates nothing.
/// Needs a current GL 4.5 context for its life; render() restores the GL state it changes.
class CausticPass {
  public:
    explicit CausticPass(CausticPassSettings settings = {}, glm::ivec2 viewport = {512, 512});
    CausticPass(CausticPassSettings settings, glm::ivec2 viewport, const ShaderLibrary& shaders);
    ~CausticPass();
    CausticPass(const CausticPass&) = delete;
    CausticPass& operator=(const CausticPass&) = delete;
    CausticPass(CausticPass&&) noexcept;
    CausticPass& operator=(CausticPass&&) noexcept;

    /// Replaces the photons with `photons`.
    void upload(std::span<const CausticPhoton> photons);
    /// Takes the photons of PhotonWorld::caustics(): each (pair, slice) has a fixed place in
    /// the buffer, and only the slices whose retrace count or size changed since the last
    /// upload are written. A change in the pairs (added, removed, other entities, counts)
    /// rewrites everything.
    void upload(std::span<const CausticPair> pairs);

    /// Splats and filters for one frame. `scene_depth` is a depth texture of camera.viewport's
    /// size (not owned; GL_TEXTURE_COMPARE_MODE must be GL_NONE), rendered with
    /// camera.view/projection. Throws luxel::Error on a non-positive viewport.
    void render(const CausticCamera& camera, GLuint scene_depth);

    /// The filtered irradiance (see the class comment); valid after render().
    [[nodiscard]] GLuint irradiance_texture() const;
    /// The photons on the GPU, as the last upload left them (what CausticLightMaps bins).
    [[nodiscard]] const CausticPhotonBuffer& photon_buffer() const;
    /// The unfiltered splat (E per pixel), for tests and debugging.
    [[nodiscard]] GLuint splat_texture() const;

    void set_settings(const CausticPassSettings& settings);
    [[nodiscard]] const CausticPassSettings& settings() const;
    /// Reads back the last render's counters and timers (waits for the GPU).
    [[nodiscard]] const CausticPassStats& stats();

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace luxel::lighting
