#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "frame_lights.hpp"
#include "frame_targets.hpp"
#include "light_batches.hpp"
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

/// The specular pass (reflections, docs/METHOD.md §8.3): one dynamic cube map ("probe") per entity
/// with a mirror or glass material, centred on its bounds, at reduced resolution. Faces are
/// rendered with forward shading of the diffuse scene (emitted + first light batch with
/// shadows + IIM; specular objects are left out of each other's probes) and refreshed on a
/// budget: a new probe renders all six faces, afterwards `faces_per_frame` faces a frame while
/// the probe is stale. A probe goes stale when its object moves, when a caster changes
/// (invalidate()) or when the caller says the lighting changed (a shadow map re-rendered, a
/// light switched, IIM pages uploaded). A converged static scene renders no probe faces.
///
/// The specular term redraws each specular object over its G-buffer depth with its probe:
/// Schlick-Fresnel-weighted reflection, plus refraction for glass (shaders/render/specular.frag).
class SpecularProbes {
  public:
    SpecularProbes(const ShaderLibrary& shaders, int size, int faces_per_frame);

    /// Something in the scene changed near `bounds`: every probe refreshes its faces.
    void invalidate(const Bounds& bounds);
    /// Refreshes probes and draws the specular term into targets.specular_target. Returns
    /// whether a term was drawn (false when there is no specular object or `draw_term` is off).
    bool render(const DrawList& draws, const std::vector<FrameLight>& lights,
                const ShadowMaps& shadows, LightBatches& batches,
                const lighting::LightmapTextures& lightmaps, const FrameTargets& targets,
                const FrameCamera& camera, double now_seconds, float blend_seconds,
                bool scene_changed, bool draw_term);
    void clear() { probes_.clear(); }

    [[nodiscard]] std::size_t count() const { return probes_.size(); }
    [[nodiscard]] std::uint64_t faces_rendered() const { return faces_rendered_; }

  private:
    struct Probe {
        gl::Texture cube;  ///< RGBA16F radiance
        gl::Renderbuffer depth;
        gl::Framebuffer framebuffer;
        glm::vec3 centre{0.0f};
        int next_face = 0;
        int stale_faces = 6;
        bool filled = false;
    };

    Probe allocate() const;
    void render_face(Probe& probe, int face, const DrawList& draws);
    void draw_term(const DrawList& draws, const FrameTargets& targets, const FrameCamera& camera);

    gl::Program probe_program_;
    gl::Program specular_program_;
    int size_;
    int faces_per_frame_;
    std::map<ecs::Entity, Probe> probes_;
    std::uint64_t faces_rendered_ = 0;
};

}  // namespace luxel::renderer
