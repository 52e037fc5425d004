#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <utility>

#include "luxel/runtime/gl_objects.hpp"
#include "luxel/scene/scene.hpp"

namespace luxel::renderer {

/// The texture unit the mesh passes (shaders/render/gbuffer.frag and cube_map_face.frag) read the
/// base-colour texture from: above every unit the G-buffer and probe passes already use
/// (shadow maps 4..11, IIM pages 12..14) and within the 16 units GL 4.5 guarantees.
inline constexpr GLuint kBaseColorTextureUnit = 15;
/// The unit the same passes read the emissive texture from. GL 4.5 guarantees 16 samplers per
/// stage but 80 combined units, so a binding above 15 is valid; these passes use two samplers.
inline constexpr GLuint kEmissiveTextureUnit = 16;

/// GL textures for scene images: one GL_SRGB8_ALPHA8 texture with a full mip chain per
/// (scene, image), sampled trilinearly (and anisotropically where the driver offers it) with
/// glTF's default REPEAT wrap. A texture is uploaded on first use and shared by every material
/// and mesh that uses the image; the cache keeps the Scene alive so its address stays a unique
/// key, and evict() frees a texture once no mesh holds it.
class MaterialTextures {
  public:
    /// The texture of `scene.images[index]`, decoded and uploaded on first use. Throws
    /// luxel::Error naming the image for undecodable data, an index out of range, or a size
    /// beyond the driver's GL_MAX_TEXTURE_SIZE.
    std::shared_ptr<const gl::Texture> get(const std::shared_ptr<const scene::Scene>& scene,
                                           int index);
    /// A 1x1 opaque white texture (sRGB 255 = linear 1): what untextured primitives sample,
    /// so that texture x factor = factor. Created on first use.
    GLuint white();
    /// Frees the textures nothing but this cache holds any more.
    void evict();

    [[nodiscard]] std::size_t size() const { return textures_.size(); }
    [[nodiscard]] std::uint64_t uploads() const { return uploads_; }

  private:
    struct Entry {
        std::shared_ptr<const scene::Scene> source;
        std::shared_ptr<const gl::Texture> texture;
    };
    /// The anisotropy to ask for: the driver's maximum (capped at 16), or 0 without
    /// EXT/ARB_texture_filter_anisotropic. Queried once.
    float anisotropy();

    std::map<std::pair<const scene::Scene*, int>, Entry> textures_;
    gl::Texture white_;
    float anisotropy_ = -1.0f;  ///< < 0: not queried yet
    std::uint64_t uploads_ = 0;
};

}  // namespace luxel::renderer
