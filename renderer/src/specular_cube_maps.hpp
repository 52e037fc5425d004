#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "frame_lights.hpp"
#include "frame_targets.hpp"
#include "light_batches.hpp"
#include "luxel/lighting/gpu/caustic_light_maps.hpp"
#include "luxel/lighting/gpu/lightmap_textures.hpp"
#include "luxel/renderer/frame_camera.hpp"
#include "luxel/runtime/gl_objects.hpp"
#include "luxel/runtime/program.hpp"
#include "scene_draws.hpp"
#include "shadow_maps.hpp"

namespace luxel {
class ShaderLibrary;
}

namespace luxel::renderer {

/// The specular term's cube maps (docs/METHOD.md §8.3; what engines call reflection cube maps, a
/// word these docs keep for photon cube maps): one dynamic cube map per entity with a mirror or
/// glass material, centred on its bounds, at reduced resolution. Faces are rendered with forward
/// shading of the diffuse scene (emitted + first light batch with shadows + IIM; specular
/// objects are left out of each other's cube maps) over the sky, where the level has one, and
/// refreshed on a budget: a new cube map
/// renders all six faces, afterwards `faces_per_frame` faces a frame while it is stale. A cube
/// map goes stale when its object moves, when a caster changes
/// (invalidate()) or when the caller says the lighting changed (a shadow map re-rendered, a
/// light switched, IIM pages uploaded). A converged static scene renders no cube-map faces.
///
/// The specular term redraws each specular object over its G-buffer depth with its cube_map:
/// Schlick-Fresnel-weighted reflection, plus refraction for glass (shaders/render/specular.frag).
class SpecularCubeMaps {
  public:
    SpecularCubeMaps(const ShaderLibrary& shaders, int size, int faces_per_frame);

    /// Something in the scene changed near `bounds`: every cube_map refreshes its faces.
    void invalidate(const Bounds& bounds);
    /// Refreshes cube maps and draws the specular term into targets.specular_target. `sky` is
    /// the frame's SkyTexture (0 without a sky: black behind the level). `caustics`: the
    /// caustic layer of the light maps the faces add (null: the scene's faces show no
    /// caustics). Returns whether a term was drawn (false when there is no specular object or
    /// `draw_term` is off).
    bool render(const DrawList& draws, const std::vector<FrameLight>& lights,
                const ShadowMaps& shadows, LightBatches& batches,
                const lighting::LightmapTextures& lightmaps,
                const lighting::CausticLightMaps* caustics, const FrameTargets& targets,
                const FrameCamera& camera, GLuint sky, double now_seconds, bool scene_changed,
                bool draw_term);
    void clear() { cube_maps_.clear(); }

    [[nodiscard]] std::size_t count() const { return cube_maps_.size(); }
    [[nodiscard]] std::uint64_t faces_rendered() const { return faces_rendered_; }
    /// Draws a face's FillBudget left out, since construction.
    [[nodiscard]] std::uint64_t skipped_draws() const { return skipped_draws_; }

  private:
    struct CubeMap {
        gl::Texture cube;  ///< RGBA16F radiance
        gl::Renderbuffer depth;
        gl::Framebuffer framebuffer;
        glm::vec3 centre{0.0f};
        int next_face = 0;
        int stale_faces = 6;
        bool filled = false;
    };

    CubeMap allocate() const;
    void render_face(CubeMap& cube_map, int face, const DrawList& draws, GLuint sky);
    void draw_term(const DrawList& draws, const FrameTargets& targets, const FrameCamera& camera);

    gl::Program face_program_;
    gl::Program sky_program_;  ///< the sky behind a face (render/cube_map_sky.frag)
    gl::VertexArray sky_triangle_ = gl::VertexArray::create();  ///< no attributes
    gl::Program specular_program_;
    int size_;
    int faces_per_frame_;
    std::map<ecs::Entity, CubeMap> cube_maps_;
    std::uint64_t faces_rendered_ = 0;
    std::uint64_t skipped_draws_ = 0;
};

}  // namespace luxel::renderer
