#pragma once

#include <cstdint>
#include <memory>

#include "luxel/lighting/core/gather.hpp"
#include "luxel/lighting/core/radiance_atlas.hpp"
#include "luxel/lighting/core/ray_scene.hpp"

namespace luxel {
class ShaderLibrary;
}

namespace luxel::lighting {

struct HemiPlaneSettings {
    /// Pixels across the plane (each texel renders resolution^2 pixels).
    int resolution = 64;
    /// a: the plane spans [-a, a]^2 at unit distance; it covers F(a) of the cosine-weighted
    /// hemisphere (F(2) = 0.831) and the rest is assumed to look like the covered part.
    float half_width = 2.0f;
    /// Texels rendered per submission (one tile each in the tile atlas). Lowered at
    /// construction if the atlas would exceed the driver's framebuffer size.
    int texels_per_batch = 256;
    /// Near plane distance as a fraction of the scene's bounding-box diagonal. Geometry closer
    /// than `near` to the texel is lost, but inside the plane's view that geometry lies within
    /// a * near of the texel's normal axis, so a texel on a floor d from a wall sees the whole
    /// wall as long as near < d / a. Depth is reversed float, so a tiny near costs no precision.
    float near_fraction = 1e-5f;
    /// CPU rays per texel and pass for the band of the hemisphere the plane misses (1 - F(a)
    /// of its cosine weight: 16.9% at a = 2), cosine-distributed over that band and traced as
    /// the CPU gather traces its rays (CpuGatherer::trace_gather_rays), while the GPU draws.
    /// 0: the band is assumed to look like what the plane sees (E = pi sum / F(a)), the
    /// paper's approximation, biased wherever the horizon differs (a floor beside a wall).
    int horizon_rays = 16;
    /// CPU rays per texel and pass over the plane's own view, for a texel whose plane shows a
    /// mirror or glass (with a material table): the plane cannot follow the bounce, so those
    /// pixels' light comes from these rays, traced through the specular surfaces to the
    /// diffuse ones they show (a floor seeing the lamp-lit ceiling through a glass sphere).
    /// Only rays whose first hit is specular count. 0: such pixels stay black.
    int specular_rays = 32;
    /// Each pass (GatherTexel::pass) turns the plane about the texel's normal by a new angle,
    /// so that averaged passes wash out its pixel grid's edges; the horizon and specular rays
    /// are new each pass either way. With neither turn nor rays every pass repeats the last
    /// and the gatherer does not refine (refines()).
    bool rotate = true;
};

/// Counters since construction, for tests and benchmarks.
struct HemiPlaneStats {
    std::uint64_t texels = 0;
    std::uint64_t batches = 0;
    std::uint64_t draws = 0;
    std::uint64_t object_uploads = 0;  ///< objects whose geometry was uploaded
    std::uint64_t page_uploads = 0;    ///< AIM pages uploaded
    std::uint64_t horizon_rays = 0;    ///< CPU rays traced for the band the plane misses
    std::uint64_t specular_rays = 0;   ///< CPU rays traced through mirrors and glass
};

/// The GPU backend of final gathering: the hemi-plane (docs/METHOD.md §6.2-6.3). From each texel
/// centre the AIM-lit scene is rendered onto one plane of half-width a at unit distance along
/// the normal, each pixel is weighted by dA / (pi (x^2 + y^2 + 1)^2), the weighted radiance is
/// summed in 32-bit float by a compute shader, and E = pi * sum + the band the plane misses:
/// pi (1 - F(a)) times the mean of `horizon_rays` CPU rays cosine-distributed over that band
/// (without them, E = pi * sum / F(a), the band assumed to look like the plane). Each pass
/// turns the plane about the normal by a new angle, so that passes average out the plane's
/// pixel grid and the band's sampling noise (docs/METHOD.md §6.3). A pixel where nothing
/// was drawn looks out of the level and reads the atlas's skies along its direction (as the CPU
/// gather's escaping rays do), through a SkyTexture.
///
/// Batching: a batch of texels_per_batch texels renders into one tile atlas (one
/// resolution^2 tile per texel) with one instanced draw per object (instance = texel; clip
/// distances keep each instance in its tile), then one compute dispatch reduces every tile of
/// the batch (one work group per tile). All batches of a gather() call write one result buffer,
/// read back once at the end of the call.
///
/// Needs a current GL 4.5 context for its whole life (construction, gather, destruction). GL
/// state that gather() changes is restored before it returns.
///
/// What is re-read per gather() call: object transforms (dynamic objects move), the object id
/// set (objects added or removed are uploaded or freed automatically: RayScene never reuses an
/// id or edits a mesh in place), the atlas's surface_page table, every page whose version
/// (or storage) changed, and the atlas's skies. refresh_geometry() forces every object to be
/// uploaded again.
class HemiPlaneGatherer final : public IrradianceGatherer {
  public:
    /// Loads the shaders from the default ShaderLibrary search paths. Throws ShaderError when
    /// they cannot be found or built, luxel::Error for invalid settings.
    HemiPlaneGatherer(const RayScene& scene, const RadianceAtlas& atlas,
                      HemiPlaneSettings settings = {});
    HemiPlaneGatherer(const RayScene& scene, const RadianceAtlas& atlas, HemiPlaneSettings settings,
                      const ShaderLibrary& shaders);
    ~HemiPlaneGatherer() override;
    HemiPlaneGatherer(const HemiPlaneGatherer&) = delete;
    HemiPlaneGatherer& operator=(const HemiPlaneGatherer&) = delete;

    [[nodiscard]] std::string_view name() const override { return "hemi-plane"; }
    /// Yes when each pass turns the plane or draws new horizon rays (the defaults).
    [[nodiscard]] bool refines() const override;
    /// Mirrors and glass drawn as such and followed by the CPU's rays (specular_rays); the
    /// geometry is uploaded again with the new table.
    void set_materials(const std::vector<TraceMaterial>* materials) override;
    void gather(std::span<const GatherTexel> texels, std::span<glm::vec3> irradiance) override;

    /// Drops the uploaded geometry; the next gather() uploads every object again.
    void refresh_geometry();

    /// The settings in use (texels_per_batch after clamping to the driver's limits).
    [[nodiscard]] const HemiPlaneSettings& settings() const;
    [[nodiscard]] const HemiPlaneStats& stats() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace luxel::lighting
