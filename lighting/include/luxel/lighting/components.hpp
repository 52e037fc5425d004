#pragma once

#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "luxel/lighting/core/sky_radiance.hpp"
#include "luxel/scene/components.hpp"
#include "luxel/scene/lightmap_layout.hpp"
#include "luxel/scene/scene.hpp"

/// The public lighting components (the generic ones every drawn entity has, MeshInstance and
/// Dynamic among them, are scene/components.hpp's): plain data a game attaches to entities, changes
/// and removes at run time. Lights shine down their entity's -z axis (the glTF convention) and are
/// placed by its WorldTransform. Units: metres, watts, linear RGB.
///
/// Change a component through Registry::patch/replace (or mark_updated after writing through a
/// reference) so the lighting system sees the change in the ECS change lists.
namespace luxel::lighting {

/// An isotropic point light emitting `power` watts per RGB channel.
struct PointLight {
    glm::vec3 power{100.0f};
    float range = 0.0f;  ///< metres beyond which it may be ignored; 0 = unbounded
    bool enabled = true;
    /// Metres: a sphere of this radius that shines with the same intensity, so its shadows have
    /// penumbrae (the frame's soft shadows, the reference's samples over the sphere). 0: a point
    /// and hard shadows. Photons leave from the centre either way (docs/METHOD.md §8.8).
    float radius = 0.0f;
};

/// A spot light: radiant intensity power / (2 pi (1 - cos outer)) inside the outer cone, with a
/// smooth falloff from the inner to the outer cone angle (radians, half angles).
struct SpotLight {
    glm::vec3 power{100.0f};
    float inner_cone = 0.3f;
    float outer_cone = 0.5f;
    float range = 0.0f;
    bool enabled = true;
    float radius = 0.0f;  ///< metres: a spherical source, as PointLight::radius
};

/// Parallel light from a distant source: `irradiance` W/m^2 on a surface facing it.
struct DirectionalLight {
    glm::vec3 irradiance{3.0f};
    bool enabled = true;
};

/// Makes the emissive primitives of the entity's MeshInstance emit: each triangle emits its
/// material's emitted radiance (W/(m^2 sr)) times `scale`, cosine-distributed.
struct AreaLight {
    float scale = 1.0f;
    bool enabled = true;
};

/// Light from the sky at infinity: `radiance` (SkyRadiance::uniform, an environment map, a
/// daylight sky) times `scale`. It lights the level through photons (which carry its light into
/// every bounce) and through the gathers, whose rays that leave the level read it (so the IIM
/// holds its direct light, with soft shadows, as for an area light); views that leave the level
/// show it. The entity's transform is not used; several enabled skies add up, as lights do.
struct SkyLight {
    std::shared_ptr<const SkyRadiance> radiance;  ///< null: black
    float scale = 1.0f;
    bool enabled = true;

    /// The scale the lighting system uses: 0 for a negative or non-finite one, at most 1e6 (with
    /// SkyRadiance's own cap every product stays finite in float).
    [[nodiscard]] float effective_scale() const {
        return scale >= 0.0f && scale <= 1e6f ? scale : (scale > 1e6f ? 1e6f : 0.0f);
    }
};

/// Marks an entity whose specular surfaces (reflective or refractive) focus light into
/// caustics. Caustic photons are emitted only toward entities with this component.
struct CausticGenerator {
    float ior = 1.5f;           ///< index of refraction of the refracting medium
    float transmission = 1.0f;  ///< 0: a mirror (reflection only), 1: clear dielectric
    glm::vec3 tint{1.0f};       ///< specular colour: the mirror's reflectance or glass tint
};

/// The light-mapped surfaces of an entity's MeshInstance, from luxel-prep's layout: each
/// surface is one primitive of the mesh with TEXCOORD_1 light-map UVs, and owns a photon map,
/// an AIM and an IIM (see scene/lightmap_layout.hpp for the fields).
struct LightmappedSurface {
    scene::LightmapLayout layout;
};

}  // namespace luxel::lighting
