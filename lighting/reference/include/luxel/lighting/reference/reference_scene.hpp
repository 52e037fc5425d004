#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/core/light_source.hpp"
#include "luxel/lighting/core/photon_tracer.hpp"
#include "luxel/lighting/core/ray_scene.hpp"

namespace luxel::lighting {
class PhotonWorld;
class IlluminationMaps;
}  // namespace luxel::lighting

/// What the reference integrator (docs/METHOD.md §10.1) knows of a scene: the geometry and
/// materials of a PhotonWorld's RayScene, its lights, and the light-map texels to estimate.
/// Nothing of the real-time estimate (photon maps, AIM, IIM) is shared, so the reference can
/// judge it.
namespace luxel::lighting::reference {

/// A light-map texel whose irradiance the reference estimates.
struct ReferenceTexel {
    glm::vec3 position{0.0f};  ///< world space, on the surface
    /// The interpolated texel normal: irradiance is measured over the hemisphere around it,
    /// as the real-time gather measures it.
    glm::vec3 normal{0.0f, 1.0f, 0.0f};
    /// The face under the texel on the normal's side: rays start off it, and directions below
    /// it (which would leave through the surface) carry nothing.
    glm::vec3 geometric{0.0f, 1.0f, 0.0f};
    std::int32_t x = 0;  ///< page texel
    std::int32_t y = 0;
    /// World m^2 of the surface inside the texel's square that a camera can see (less than a
    /// full texel at a chart's border, and under an object resting on the surface: measured at
    /// 8 x 8 points per texel); the weight of docs/METHOD.md §10.2's relRMSE and the divisor of
    /// the photon bins. 0 for a texel wholly under an object: it has no reference value.
    double area = 0.0;
};

/// One light-mapped surface: a PhotonWorld surface id (RayHit::surface) and its texels.
struct ReferenceSurface {
    std::uint32_t surface = 0;
    int page = 0;  ///< the surface's light-map page (luxel-prep's page index)
    int page_size = 0;
    std::vector<ReferenceTexel> texels;
    std::size_t first_texel = 0;  ///< index of texels[0] among all the scene's texels
};

/// A light as the reference samples it.
struct ReferenceLight {
    LightSource source;
    TriangleSampler triangles;  ///< area lights: the emitting triangles
    TriangleSampler portals;    ///< skies: the level's portals (empty: none)
    /// Point and spot: radiant intensity on the axis, W/sr (spot: before the falloff).
    glm::vec3 intensity{0.0f};

    /// Point, spot and directional lights: no path can hit them, so their caustics come from
    /// photons (CausticReference). Area lights and skies are hit and path traced.
    [[nodiscard]] bool is_delta() const {
        return source.kind != LightKind::Area && source.kind != LightKind::Sky;
    }
};

/// Where a ray met an area light: the light and the triangle of its LightSource::triangles.
struct EmitterHit {
    std::int32_t light = -1;  ///< -1: not an emitter
    std::uint32_t triangle = 0;
};

class HitTextures;

class ReferenceScene {
  public:
    /// `rays` must outlive the scene and stay unchanged (committed) while it is used.
    /// `surfaces` are given with their texels' position, normal and x, y; the constructor finds
    /// each texel's face and area from the geometry. Throws luxel::Error for a material id a
    /// triangle names but `materials` lacks.
    ReferenceScene(const RayScene& rays, std::vector<TraceMaterial> materials,
                   std::vector<LightSource> lights, std::vector<ReferenceSurface> surfaces);

    /// The geometry, materials and enabled lights of `world`, and the texels of every surface
    /// of `maps` that has a light map. Both must be synced.
    [[nodiscard]] static ReferenceScene from_world(const PhotonWorld& world,
                                                   const IlluminationMaps& maps);
    /// The texels from_world would take from `maps`, counted without allocating anything: a
    /// tool checks its memory limit with it before building the scene.
    [[nodiscard]] static std::size_t count_texels(const IlluminationMaps& maps);

    [[nodiscard]] const RayScene& rays() const { return *rays_; }
    [[nodiscard]] std::span<const TraceMaterial> materials() const { return materials_; }
    /// Tests edit materials (the furnace at another albedo) before integrating.
    [[nodiscard]] std::span<TraceMaterial> materials() { return materials_; }
    /// The diffuse albedo at a hit on `material`: its base-colour texture there when the scene
    /// came from a world with textured meshes (HitTextures), else the material's albedo.
    [[nodiscard]] glm::vec3 diffuse_albedo(const RayHit& hit, const TraceMaterial& material) const;
    /// Whether hits read base-colour textures (a world with textured meshes).
    [[nodiscard]] bool textured() const { return textures_ != nullptr; }
    [[nodiscard]] std::span<const ReferenceLight> lights() const { return lights_; }
    [[nodiscard]] std::span<const ReferenceSurface> surfaces() const { return surfaces_; }
    [[nodiscard]] std::size_t texel_count() const { return texel_count_; }
    /// The texel of global index i.
    [[nodiscard]] const ReferenceTexel& texel(std::size_t index) const;
    /// Every texel's area, in global texel order.
    [[nodiscard]] std::vector<double> texel_areas() const;

    /// The light (and its triangle) whose emitting triangle `hit` is (front or back); light -1
    /// when none.
    [[nodiscard]] EmitterHit emitter_of(const RayHit& hit) const;
    /// The radiance W/(m^2 sr) an area light emits at a hit on it, and the density per m^2 with
    /// which its sampler picks that point (for weighing the two strategies).
    struct Emission {
        glm::vec3 radiance{0.0f};
        double density = 0.0;
    };
    [[nodiscard]] Emission emission_at(const EmitterHit& emitter, const glm::vec3& point) const;
    /// The global texel a hit's light-map UV falls into, or -1 (surface without a light map,
    /// or a UV outside the surface's texels).
    [[nodiscard]] std::int64_t texel_at(std::int32_t surface, const glm::vec2& lightmap_uv) const;
    /// As texel_at, or -1 where the point lies in the part of its texel an object rests on
    /// (ReferenceTexel::area leaves it out): photons landing there are not binned, so a bin
    /// holds the light on the part of the texel that counts.
    [[nodiscard]] std::int64_t open_texel_at(std::int32_t surface,
                                             const glm::vec2& lightmap_uv) const;
    /// Bounding spheres of every object with specular (mirror or dielectric) triangles, around
    /// those triangles: what caustic photons are aimed at. Derived from the geometry, not from
    /// CausticGenerator components, so untagged specular objects are not missed.
    [[nodiscard]] std::span<const BoundingSphere> generator_spheres() const { return specular_; }
    [[nodiscard]] BoundingSphere bounds() const { return bounds_; }

  private:
    void find_emitters();
    void find_specular_objects();
    void measure_texels();

    const RayScene* rays_;
    std::vector<TraceMaterial> materials_;
    std::shared_ptr<const HitTextures> textures_;  ///< null: every hit reads its material
    std::vector<ReferenceLight> lights_;
    std::vector<ReferenceSurface> surfaces_;
    std::size_t texel_count_ = 0;
    std::vector<std::int32_t> surface_slot_;  ///< PhotonWorld surface id -> surfaces_ index
    /// Per surface slot: page texel (y * size + x) -> global texel index.
    std::vector<std::unordered_map<std::int64_t, std::uint32_t>> texel_lookup_;
    /// Per global texel, 8 x 8 sub-points (row by row): 2 where an object
    /// rests on the surface there (measure_texels), else open.
    std::vector<std::uint8_t> sub_points_;
    /// (object << 32 | triangle) -> light index, for area lights' triangles.
    std::unordered_map<std::uint64_t, EmitterHit> emitters_;
    std::vector<BoundingSphere> specular_;
    BoundingSphere bounds_;
};

}  // namespace luxel::lighting::reference
