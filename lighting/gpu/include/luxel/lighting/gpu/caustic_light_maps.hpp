#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/core/illumination_maps.hpp"
#include "luxel/runtime/gl_objects.hpp"
#include "luxel/runtime/program.hpp"

namespace luxel {
class ShaderLibrary;
}

namespace luxel::lighting {

class CausticPass;

/// The caustic layer of the light maps (docs/METHOD.md §7.7): caustic irradiance (W/m^2 per
/// channel) per light-map texel, for the views that the camera's screen-space caustics cannot
/// serve. The specular cube maps sample it, so a pool floor seen through its water, or a
/// caustic seen in a mirror, carries its caustic light.
///
/// One RGBA32F 2D array texture with a layer per IIM page, each page in its layer's corner as
/// LightmapTextures places it, so a shader that finds a surface's IIM texel finds its caustic
/// texel at the same coordinates. rgb: irradiance; a: photons binned.
///
/// Built on the GPU from the photons the CausticPass already holds: each photon on a
/// light-mapped surface is drawn as one point at its light-map UV into its page's layer (a
/// geometry shader picks the layer) with additive blending, adding power / (the texel's world
/// area, world_metres_per_texel^2): the per-texel binning luxel-bench measures the caustic light
/// maps with (docs/RESULTS.md), so the measured error is the error these views show. The layer
/// is redrawn whole when the pass's photons or the surfaces (pages, surface pages, scale)
/// changed since the last sync, never otherwise.
///
/// Needs a current GL 4.5 context for its life; sync() restores the GL state it changes.
class CausticLightMaps {
  public:
    explicit CausticLightMaps(const ShaderLibrary& shaders);

    /// Redraws the layer if `caustics`' photons or `maps`' surfaces changed since the last
    /// call; returns whether it did.
    bool sync(const CausticPass& caustics, const IlluminationMaps& maps);

    /// The texture unit shaders/render/caustic_light_map.glsl reads the layer at (clear of the
    /// units the cube maps' faces and the composite bind otherwise).
    static constexpr GLuint kTextureUnit = 20;
    /// Binds the layer at kTextureUnit (nothing while empty()).
    void bind() const;

    /// No page: nothing to sample (texture() is 0).
    [[nodiscard]] bool empty() const { return layers_ == 0; }
    [[nodiscard]] GLuint texture() const { return texture_.id(); }
    [[nodiscard]] int layers() const { return layers_; }
    [[nodiscard]] int layer_size() const { return layer_size_; }
    /// Times the layer was redrawn since construction.
    [[nodiscard]] std::uint64_t redraws() const { return redraws_; }

  private:
    /// Per surface: page layer (-1: none), page size, 1 / texel area (m^-2), unused.
    [[nodiscard]] static std::vector<glm::vec4> surface_table(const IlluminationMaps& maps);
    void allocate(const IlluminationMaps& maps);
    void draw(const CausticPass& caustics);

    gl::Program program_;
    gl::VertexArray empty_vertex_array_ = gl::VertexArray::create();
    gl::Texture texture_;
    gl::Framebuffer framebuffer_;
    gl::Buffer surfaces_;
    std::vector<int> page_sizes_;
    std::vector<glm::vec4> table_;
    int layers_ = 0;
    int layer_size_ = 0;
    std::uint64_t slices_seen_ = 0;
    GLuint buffer_seen_ = 0;
    bool drawn_ = false;
    std::uint64_t redraws_ = 0;
};

}  // namespace luxel::lighting
