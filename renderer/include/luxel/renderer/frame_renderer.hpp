#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string_view>

#include "luxel/ecs/registry.hpp"
#include "luxel/lighting/gpu/caustic_pass.hpp"
#include "luxel/renderer/frame_camera.hpp"
#include "luxel/runtime/gl.hpp"
#include "luxel/runtime/image.hpp"

namespace luxel {
class ShaderLibrary;
}
namespace luxel::lighting {
class LightingSystem;
}

namespace luxel::renderer {

struct FrameSettings {
    int width = 1280;
    int height = 720;
    int cube_shadow_size = 512;  ///< texels per cube face edge (point lights, wide spots)
    int map_shadow_size = 1024;  ///< texels per edge of 2D maps (spot, directional)
    /// 3 x 3 PCF of bilinear comparisons (soft edges); false: one hard comparison per pixel.
    bool filtered_shadows = true;
    /// Lights with a radius (PointLight::radius, SpotLight::radius) cast soft shadows: the
    /// image-space gathering of R.-H. Yao's thesis, a blocker search and a penumbra-wide filter
    /// over the G-buffer (docs/METHOD.md §8.8). false: every light's shadows are hard. Frames
    /// whose lights are all points run no extra pass either way.
    bool soft_shadows = true;
    /// Smooths the frame's geometric edges after the composite (docs/METHOD.md §8.4): pixels
    /// where the G-buffer shows two surfaces meeting take the mix of both sides their coverage
    /// gives; every other pixel is the composite's exactly. false: no edge pass, no extra target.
    bool anti_aliasing = true;
    /// Light maps read through a cubic B-spline (16 texels) instead of bilinearly (4): smooth
    /// gradients without the texel grid's creases at the same texel count, slightly blurred
    /// (render/iim.glsl). Levels prepared with `luxel-prep --padding 2` keep its wider
    /// footprint inside each chart's gutter.
    bool bicubic_light_maps = false;
    /// Where the frame has a sky: how much of each pixel shows it, from every surface drawn
    /// again at 4 x 4 sub-samples a pixel without shading, and the sky and the surfaces mixed
    /// by that fraction at silhouettes against it (docs/METHOD.md §8.6). A bright sky through a
    /// window otherwise puts most of the frame's error in the window's one-pixel border.
    /// false: no such pass and no mask.
    bool sky_edge_coverage = true;
    /// Skinned meshes skinned in the vertex stage (render/skinning.glsl, docs/METHOD.md §8.7):
    /// their bind mesh uploaded once, each frame's joint matrices in one storage buffer. false:
    /// the CPU's pose (MeshInstance::posed) is uploaded each time it changes, 40 bytes a vertex.
    bool gpu_skinning = true;
    /// Wait for this frame's GPU timer queries in render() (benchmarks, tests). Otherwise
    /// render() reports the latest frame whose queries are done, without stalling the GPU.
    bool wait_for_timings = false;
    /// The specular pass: a cube map per specular object (mirror or glass) of this edge,
    /// re-rendered `specular_faces_per_frame` faces per frame.
    int specular_cube_size = 128;
    int specular_faces_per_frame = 1;
    /// The caustic render pass the renderer creates while the FeaturePlan has caustic data (and
    /// frees when it has none), run on each frame's own depth between the G-buffer and the
    /// composite. nullopt: the renderer makes no caustics itself (set_caustics or
    /// set_caustic_stage may still supply them).
    /// The default kernel is the photon footprints (ray differentials): of the estimators
    /// luxel-bench compares against the caustic at pixel resolution it had the lowest error on
    /// the caustics level from 3 m to 0.8 m (a tie with the mip-maps at 6.3 m), the lowest
    /// image error at the level's camera, and by far the lowest on cornell, whose small bright
    /// foci every per-pixel widening spreads (docs/RESULTS.md, "Close-ups").
    std::optional<lighting::CausticPassSettings> caustics =
        lighting::CausticPassSettings{.kernel = lighting::CausticKernel::PhotonFootprints};
    /// The camera's caustics on light-mapped pixels read from the caustic layer of the light
    /// maps (docs/METHOD.md §7.7: photons binned per texel, read at the nearest texel) instead
    /// of the screen-space pass where a texel covers at most about a pixel (close up, where a
    /// texel spans two pixels or more, the pass keeps a pixel's detail); pixels without a
    /// light map keep the pass. Needs `caustics`; caustics from set_caustics or a stage are
    /// shown as they are. Off by default since the footprints kernel: the layer beat Larsen's
    /// screen-space kernel (caustics level image 6.9% against 7.9%), but the footprints beat
    /// the layer (6.8%; the caustic term 18.7% against 23.2%, cornell's 14.3% against 48%).
    /// Views other than the camera's read the layer whatever this says.
    bool caustic_layer_in_view = false;
};

/// Which terms of the composition go into the frame (the sandbox's keys, README pictures).
struct FrameTerms {
    bool direct = true;
    bool indirect = true;
    bool caustics = true;
    bool specular = true;
    bool emission = true;  ///< emitters' own radiance (area lights seen directly)
};

/// The GPU passes of a frame, in order.
enum class RenderPass : std::uint8_t {
    Shadows,
    GBuffer,
    Direct,
    Indirect,
    Specular,
    Composite,
    AntiAliasing,
    SkyEdges,    ///< SkyCoverage's mask, while the frame has a sky
    SoftShadows  ///< the direct light of lights with a radius (SoftShadows), while there are any
};
inline constexpr std::size_t kRenderPassCount = 9;
/// "shadows", "gbuffer", ...
[[nodiscard]] std::string_view name(RenderPass pass);

/// GPU time per pass from timer queries (0 for a pass that did not run).
struct FrameTimings {
    std::uint64_t frame = 0;  ///< the frame these times belong to (0: none measured yet)
    std::array<double, kRenderPassCount> milliseconds{};

    [[nodiscard]] double operator[](RenderPass pass) const {
        return milliseconds[static_cast<std::size_t>(pass)];
    }
    [[nodiscard]] double total() const;
};

/// Counts for tests, the HUD and the report.
struct FrameCounters {
    std::uint64_t frames = 0;
    std::size_t shadow_maps = 0;           ///< allocated now
    std::size_t shadow_maps_drawn = 0;     ///< re-rendered this frame
    std::uint64_t shadow_map_renders = 0;  ///< since construction
    std::size_t lights = 0;                ///< enabled punctual lights this frame
    std::size_t soft_lights = 0;           ///< of them drawn with soft shadows
    std::size_t draws = 0;                 ///< primitives drawn into the G-buffer this frame
    std::size_t meshes_cached = 0;         ///< (scene, mesh) pairs with GPU buffers
    std::uint64_t mesh_uploads = 0;        ///< meshes uploaded, since construction
    std::size_t joint_matrices = 0;        ///< skinned in the vertex stage this frame
    std::uint64_t page_uploads = 0;        ///< IIM page rectangles uploaded, since construction
    std::uint64_t texels_uploaded = 0;     ///< IIM texels uploaded, since construction
    std::uint64_t probe_uploads = 0;       ///< irradiance probe uploads, since construction
    std::size_t specular_cube_maps = 0;    ///< specular cube maps allocated now
    std::uint64_t specular_faces = 0;      ///< specular cube faces rendered, since construction
    /// Primitives left out of a shadow map or a specular cube face because the view was
    /// already covered many times over (geometry stacked on itself), since construction.
    std::uint64_t draws_over_fill_budget = 0;
};

/// A caustic term produced elsewhere (the caustic splat/filter pass): a texture of the frame's
/// size, per pixel either irradiance W/m^2 (multiplied by albedo / pi in the composition) or
/// radiance. texture 0: no caustics.
struct CausticInput {
    GLuint texture = 0;
    bool irradiance = true;
};

/// Draws the caustic term of the frame being rendered: called by render() after the G-buffer
/// and before the composite, with the frame's camera and the G-buffer's depth texture
/// (DEPTH_COMPONENT32F, the camera's projection) to depth-test splats against. What it returns
/// is composited into the same frame. It may change any GL state: render() restores its own.
using CausticStage = std::function<CausticInput(const FrameCamera& camera, GLuint depth_texture)>;

/// Which image read() returns (all linear, rows top first).
enum class FrameImage : std::uint8_t {
    Frame,     ///< the composed frame L
    Direct,    ///< sum_i L_direct(i) * shadow(i)
    Indirect,  ///< L_indirect from the IIM
    Specular,  ///< L_specular
    Albedo,    ///< diffuse albedo (rgb), 1 in alpha where a specular material is
};

/// The frame: shadows -> G-buffer -> direct -> IIM -> specular -> composite, in linear HDR
/// radiance W/(m^2 sr) (docs/METHOD.md §1.2 step 5, §8 composition).
///
///     FrameRenderer renderer(registry, lighting, {.width = 1280, .height = 720});
///     each frame, after lighting.update(budget, t):
///         renderer.set_caustic_stage(...);   // optional: CausticPass on this frame's depth
///         const FrameTimings& times = renderer.render(camera, t);
///         tone-map renderer.frame_texture() for display, or renderer.read(FrameImage::Frame)
///
/// What it reads: MeshInstance + WorldTransform (what to draw), PointLight / SpotLight /
/// DirectionalLight (+ WorldTransform), AreaLight (emitters' scale and switch), the
/// LightingSystem's FeaturePlan, IIM pages and surfaces. Passes exist only when the plan says
/// the scene needs them: no enabled light, no shadow maps and no direct pass; no specular
/// material, no cube maps.
///
/// Shadow maps are re-rendered only when their light moved or changed shape (position,
/// direction, cone, or the scene bounds that set its far plane) or when a mesh whose bounds
/// reach the light's range was added, removed or moved. Motion comes from ecs Observers of
/// WorldTransform and MeshInstance (O(changes) per frame).
///
/// IIM pages are uploaded where their version changed: the rectangle that changed since this
/// renderer's last upload (RadiancePage::changes_since). The renderer only reads the lighting
/// system, so several renderers (the sandbox's, luxel-bench's frame view) can follow one.
///
/// Needs a current GL 4.5 context for its whole life. Restores the GL state it changes.
class FrameRenderer {
  public:
    /// Loads the shaders from the default ShaderLibrary search paths.
    FrameRenderer(ecs::Registry& registry, const lighting::LightingSystem& lighting,
                  FrameSettings settings = {});
    FrameRenderer(ecs::Registry& registry, const lighting::LightingSystem& lighting,
                  FrameSettings settings, const ShaderLibrary& shaders);
    ~FrameRenderer();
    FrameRenderer(const FrameRenderer&) = delete;
    FrameRenderer& operator=(const FrameRenderer&) = delete;

    /// Renders the frame seen by `camera` at `now_seconds` (the clock the IIM blend uses: the
    /// one passed to LightingSystem::update). Returns GPU times per pass (see
    /// FrameSettings::wait_for_timings).
    const FrameTimings& render(const FrameCamera& camera, double now_seconds);

    void set_terms(const FrameTerms& terms);
    [[nodiscard]] const FrameTerms& terms() const;
    /// A caustic term made elsewhere, composited into the next frames ({} to remove it).
    void set_caustics(const CausticInput& caustics);
    /// The caustic term made during each frame (see CausticStage; {} to remove it). While a
    /// stage is set it replaces set_caustics(), and set_caustics() replaces the renderer's own
    /// caustic pass (FrameSettings::caustics).
    void set_caustic_stage(CausticStage stage);
    /// The renderer's own caustic pass (its statistics), or null while the plan has no caustic
    /// data or FrameSettings::caustics is nullopt.
    [[nodiscard]] lighting::CausticPass* caustic_pass();
    /// Reallocates the frame's targets.
    void resize(int width, int height);

    /// The composed frame: RGBA32F linear radiance (alpha 1).
    [[nodiscard]] GLuint frame_texture() const;
    /// Its framebuffer (colour attachment 0), e.g. to blit to a window.
    [[nodiscard]] GLuint frame_framebuffer() const;
    /// The G-buffer's depth (DEPTH_COMPONENT32F, the camera's projection), for passes that
    /// depth-test against the scene (caustic splats).
    [[nodiscard]] GLuint depth_texture() const;
    /// The G-buffer's world positions (RGBA32F, w = 1 where geometry is) and normals.
    [[nodiscard]] GLuint position_texture() const;
    [[nodiscard]] GLuint normal_texture() const;
    /// The G-buffer's light-map lookup (RGBA32F: UV, IIM page layer, content; layer < 0 where
    /// a pixel has no light map and the irradiance probes light it).
    [[nodiscard]] GLuint lightmap_texture() const;
    /// Reads an image back (for EXR: write_exr(path, renderer.read(FrameImage::Frame))).
    [[nodiscard]] Image read(FrameImage image = FrameImage::Frame) const;

    [[nodiscard]] const FrameTimings& timings() const;
    [[nodiscard]] const FrameCounters& counters() const;
    [[nodiscard]] const FrameSettings& settings() const;
    /// Shadow maps allocated now (0 in a scene without lights).
    [[nodiscard]] std::size_t shadow_map_count() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace luxel::renderer
