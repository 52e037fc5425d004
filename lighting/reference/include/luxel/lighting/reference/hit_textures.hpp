#pragma once

#include <map>
#include <memory>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/core/photon_world.hpp"
#include "luxel/lighting/core/ray_scene.hpp"
#include "luxel/scene/texture_mean.hpp"

namespace luxel::lighting::reference {

/// Base-colour textures at ray hits, for the reference's paths. The renderer multiplies each
/// pixel's light by the texture at that pixel; the photons and the light maps bounce with the
/// texture's mean (scene::mean_diffuse_albedo), which is enough for light that has already
/// spread over many texels. A reference frame of a textured level must show the texture where
/// the camera looks, so the reference reads it at every diffuse hit: the material's base-colour
/// factor (clamped to [0, 1]) times the texture at the hit's TEXCOORD_0, bilinear with REPEAT,
/// as the renderer samples it.
///
/// Only luxel-ref builds this: the real-time world keeps no texture coordinates for rays. It
/// holds, per object of the ray scene, the vertices' TEXCOORD_0 and each triangle's texture,
/// and each distinct image decoded once (8-bit, decoded to linear per read:
/// scene::LinearImage).
class HitTextures {
  public:
    /// The textures of every mesh `world` mirrors; null when no triangle of it is textured.
    /// An image that does not decode is left out with a warning naming it (its triangles keep
    /// their material's mean albedo).
    [[nodiscard]] static std::shared_ptr<const HitTextures> from_world(const PhotonWorld& world);

    /// The diffuse albedo at `hit`, or nothing when its triangle has no base-colour texture
    /// (the caller uses its material's).
    [[nodiscard]] std::optional<glm::vec3> albedo(const RayHit& hit) const;

    /// Distinct images decoded.
    [[nodiscard]] std::size_t image_count() const { return images_.size(); }

  private:
    struct Texture {
        const scene::LinearImage* image = nullptr;
        glm::vec3 factor{1.0f};
    };
    struct Object {
        std::vector<glm::vec2> texcoords;    ///< per vertex of the ray scene's mesh
        std::vector<std::int32_t> textures;  ///< per triangle: index into textures_, -1 none
        const TriangleMesh* mesh = nullptr;  ///< the ray scene's, for the triangles' vertices
    };

    std::vector<std::unique_ptr<scene::LinearImage>> images_;
    std::vector<Texture> textures_;
    std::map<ObjectId, Object> objects_;
};

}  // namespace luxel::lighting::reference
