#include "luxel/renderer/frame_renderer.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "composite_pass.hpp"
#include "edge_anti_aliasing.hpp"
#include "fill_budget.hpp"
#include "frame_lights.hpp"
#include "frame_targets.hpp"
#include "indirect_pass.hpp"
#include "light_batches.hpp"
#include "luxel/ecs/observer.hpp"
#include "luxel/ecs/transform.hpp"
#include "luxel/lighting/core/lighting_system.hpp"
#include "luxel/lighting/gpu/irradiance_probe_textures.hpp"
#include "luxel/lighting/gpu/lightmap_textures.hpp"
#include "luxel/lighting/gpu/sky_texture.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/runtime/gl_state_guard.hpp"
#include "luxel/runtime/log.hpp"
#include "luxel/runtime/program_variants.hpp"
#include "luxel/runtime/render_target.hpp"
#include "luxel/runtime/shader_library.hpp"
#include "mesh_cache.hpp"
#include "own_caustics.hpp"
#include "pass_timer.hpp"
#include "scene_draws.hpp"
#include "shadow_maps.hpp"
#include "sky_coverage.hpp"
#include "soft_shadows.hpp"
#include "specular_cube_maps.hpp"

namespace luxel::renderer {
namespace {

void validate(const FrameSettings& s) {
    const auto positive = [](int value, const char* what) {
        if (value < 1 || value > 16384) {
            throw Error(std::string("FrameSettings.") + what + " must be in [1, 16384], got " +
                        std::to_string(value));
        }
    };
    positive(s.width, "width");
    positive(s.height, "height");
    positive(s.cube_shadow_size, "cube_shadow_size");
    positive(s.map_shadow_size, "map_shadow_size");
    positive(s.specular_cube_size, "specular_cube_size");
    if (s.specular_faces_per_frame < 0) {
        throw Error("FrameSettings.specular_faces_per_frame must not be negative");
    }
}

void draw_fullscreen() {
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

void clear_colour(GLuint framebuffer, GLint buffer = 0) {
    const std::array<float, 4> zero = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearNamedFramebufferfv(framebuffer, GL_COLOR, buffer, zero.data());
}

}  // namespace

struct FrameRenderer::Impl {
    ecs::Registry& registry;
    const lighting::LightingSystem& lighting;
    FrameSettings settings;
    gl::Program gbuffer_program;
    gl::Program shadow_program;
    /// The direct pass in the variant each light batch needs (its shadow-map shapes).
    ProgramVariants direct_programs;
    IndirectPass indirect_light;
    CompositePass composite;
    gl::VertexArray fullscreen = gl::VertexArray::create();
    FrameTargets targets;
    MeshCache meshes;
    DrawList draws;
    ShadowMaps shadows;
    std::uint64_t gbuffer_skipped = 0;  ///< draws the G-buffer's FillBudget left out, in all
    lighting::LightmapTextures lightmaps;
    /// The irradiance probes, while the lighting system has them (receivers without a light map).
    lighting::IrradianceProbeTextures probes;
    lighting::SkyTexture sky;  ///< the lighting system's skies, behind everything drawn
    SpecularCubeMaps cube_maps;
    std::optional<EdgeAntiAliasing> anti_aliasing;  ///< FrameSettings::anti_aliasing
    std::optional<SoftShadows>
        soft_shadows;  ///< from the first frame with a light that has a radius
    /// FrameSettings::sky_edge_coverage, while the frame has a sky.
    std::optional<SkyCoverage> sky_edges;
    bool sky_masked = false;  ///< this frame has sky_edges' mask
    /// This frame's caustics come from the own pass (not set_caustics or a stage): only then
    /// may FrameSettings::caustic_layer_in_view replace them on light-mapped pixels.
    bool own_caustics_shown = false;
    PassTimer timer;
    FrameTimings timings;
    FrameCounters counters;
    FrameTerms terms;
    CausticInput caustics;  ///< set_caustics(): a caustic term made elsewhere
    CausticStage caustic_stage;
    ShaderLibrary shader_library;              ///< for the passes made later (the caustic pass)
    OwnCaustics own_caustics{shader_library};  ///< FrameSettings::caustics
    LightBatches batches;
    gl::Texture black = gl::Texture::create_2d(GL_RGBA16F, 1, 1);
    ecs::Observer<scene::MeshInstance> mesh_changes;
    ecs::Observer<ecs::WorldTransform> moves;
    /// World bounds of every mesh entity as last seen: where a moved or removed caster was.
    std::map<ecs::Entity, Bounds> caster_bounds;
    std::uint64_t frame = 0;
    std::size_t previous_light_count = 0;
    std::uint64_t previous_page_uploads = 0;

    Impl(ecs::Registry& r, const lighting::LightingSystem& l, const FrameSettings& s,
         const ShaderLibrary& shaders)
        : registry(r),
          lighting(l),
          settings(s),
          gbuffer_program(shaders.build({{ShaderStage::Vertex, "render/mesh.vert"},
                                         {ShaderStage::Fragment, "render/gbuffer.frag"}})),
          shadow_program(shaders.build({{ShaderStage::Vertex, "render/shadow.vert"},
                                        {ShaderStage::Fragment, "render/shadow.frag"}})),
          direct_programs(
              shaders, "post/fullscreen.vert", "render/direct.frag",
              {"CUBE_SHADOWS", "MAP_SHADOWS"},
              "#define LIGHTS_PER_BATCH " + std::to_string(LightBatches::kLightsPerBatch) + "\n"),
          indirect_light(shaders),
          composite(shaders),
          targets(s.width, s.height, s.anti_aliasing),
          shadows(s.cube_shadow_size, s.map_shadow_size),
          cube_maps(shaders, s.specular_cube_size, s.specular_faces_per_frame),
          shader_library(shaders),
          mesh_changes(r.observe<scene::MeshInstance>(ecs::ObserverStart::WithExisting)),
          moves(r.observe<ecs::WorldTransform>()) {
        if (s.anti_aliasing) {
            anti_aliasing.emplace(shaders);
        }
        const std::array<std::uint16_t, 4> zero{};  // half floats: 0
        glTextureSubImage2D(black.id(), 0, 0, 0, 1, 1, GL_RGBA, GL_HALF_FLOAT, zero.data());
        gl::check_error("FrameRenderer");
    }

    /// Bounds of a mesh entity now, or empty when it has no drawable mesh.
    Bounds bounds_now(ecs::Entity entity) {
        if (!registry.valid(entity)) {
            return {};
        }
        const auto* instance = registry.try_get<scene::MeshInstance>(entity);
        if (instance == nullptr || !instance->source || instance->mesh < 0 ||
            static_cast<std::size_t>(instance->mesh) >= instance->source->meshes.size()) {
            return {};
        }
        return meshes.bounds(*instance, frame).transformed(entity_world_matrix(registry, entity));
    }

    /// A caster appeared, moved or went: shadow maps that reach where it was or is are stale.
    void caster_changed(ecs::Entity entity, bool exists) {
        const auto found = caster_bounds.find(entity);
        if (found != caster_bounds.end()) {
            shadows.invalidate(found->second);
            cube_maps.invalidate(found->second);
            caster_bounds.erase(found);
        }
        if (exists) {
            const Bounds now = bounds_now(entity);
            if (!now.empty()) {
                shadows.invalidate(now);
                cube_maps.invalidate(now);
                caster_bounds[entity] = now;
            }
        }
    }

    void track_changes() {
        mesh_changes.consume([&](ecs::Entity entity, ecs::ChangeKind kind) {
            caster_changed(entity, kind != ecs::ChangeKind::Destroyed);
        });
        moves.consume([&](ecs::Entity entity, ecs::ChangeKind kind) {
            if (kind == ecs::ChangeKind::Destroyed || caster_bounds.contains(entity)) {
                caster_changed(entity, kind != ecs::ChangeKind::Destroyed &&
                                           registry.valid(entity) &&
                                           registry.has<scene::MeshInstance>(entity));
            }
        });
    }

    void gbuffer_pass(const FrameCamera& camera) {
        const GLuint fbo = targets.gbuffer.id();
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
        glViewport(0, 0, targets.width, targets.height);
        for (GLint buffer = 0; buffer < 6; ++buffer) {
            clear_colour(fbo, buffer);
        }
        // Light-map lookups of empty pixels name no page (layer -1), so they read nothing.
        const std::array<float, 4> no_page = {0.0f, 0.0f, -1.0f, 0.0f};
        glClearNamedFramebufferfv(fbo, GL_COLOR, 3, no_page.data());
        const float far_depth = 1.0f;
        glStencilMask(0xFF);
        glClearNamedFramebufferfi(fbo, GL_DEPTH_STENCIL, 0, far_depth, 0);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        // The stencil says which visible surface has no light map (1): the indirect pass gives
        // those pixels the probes' light in a pass of their own.
        glEnable(GL_STENCIL_TEST);
        glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
        const gl::Program& program = gbuffer_program;
        program.use();
        const glm::mat4 view_projection = camera.projection * camera.view;
        program.set("u_view_projection", view_projection);
        program.set("u_camera", camera.position);
        std::size_t drawn = 0;
        // Geometry stacked on itself is left out past the budget, as in the shadow maps
        // (fill_budget.hpp): a real level covers the frame a few times, not thousands.
        FillBudget budget(static_cast<double>(targets.width) * static_cast<double>(targets.height));
        draw_in_view(
            draws, view_projection, targets.width, targets.height, budget,
            [](const DrawItem&) { return true; },
            [&](const DrawItem& item) { bind_draw_item(program, item); },
            [&](const DrawItem& item, const DrawPrimitive& primitive) {
                const DrawMaterial& m = primitive.material;
                cull_as_material(item, m);
                program.set("u_albedo", m.albedo);
                // Texture x factor per pixel (white for untextured primitives).
                glBindTextureUnit(kBaseColorTextureUnit, m.base_color_texture);
                glBindTextureUnit(kEmissiveTextureUnit, m.emissive_texture);
                program.set("u_emission", m.emission);
                program.set("u_specular", m.specular);
                program.set("u_lightmap", m.lightmap);
                glStencilFunc(GL_ALWAYS, m.lightmap.x < 0.0f ? 1 : 0, 0xFF);
                program.set("u_double_sided", m.double_sided ? 1 : 0);
                draw_primitive(*primitive.range);
                ++drawn;
            });
        counters.draws = drawn;
        if (budget.skipped() > 0 && gbuffer_skipped == 0) {
            log::warn("the frame's draws would cover about ", budget.wanted(), " of its ",
                      targets.width * targets.height, " pixels (", FillBudget::kLayers,
                      " layers allowed): the level stacks geometry on itself; ", budget.skipped(),
                      " primitives are left out of the frame");
        }
        gbuffer_skipped += budget.skipped();
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_STENCIL_TEST);
        glDisable(GL_CULL_FACE);
        glFrontFace(GL_CCW);
    }

    void direct_pass(const std::vector<FrameLight>& lights) {
        const GLuint fbo = targets.direct_target.id();
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
        glViewport(0, 0, targets.width, targets.height);
        clear_colour(fbo);
        // Batches add up: L = sum over lights.
        glEnable(GL_BLEND);
        glBlendEquation(GL_FUNC_ADD);
        glBlendFunc(GL_ONE, GL_ONE);
        glBindTextureUnit(0, targets.albedo.id());
        glBindTextureUnit(1, targets.normal.id());
        glBindTextureUnit(2, targets.position.id());
        for (std::size_t batch = 0; batch < LightBatches::batch_count(lights.size()); ++batch) {
            const gl::Program& program =
                direct_programs.get(LightBatches::shadow_shapes(lights, batch, shadows));
            program.use();
            program.set("u_filtered", settings.filtered_shadows ? 1 : 0);
            batches.bind(lights, batch, shadows);
            draw_fullscreen();
        }
        glDisable(GL_BLEND);
    }

    void indirect_pass(const FrameCamera& camera, double now_seconds) {
        indirect_light.run(targets, camera, now_seconds, settings.bicubic_light_maps, lightmaps,
                           probes);
    }

    void composite_pass(const FrameCamera& camera, bool direct, bool indirect, bool specular) {
        CompositeInputs in;
        in.direct = direct;
        in.indirect = indirect;
        in.specular = specular;
        in.emission = terms.emission;
        in.caustics = terms.caustics ? caustics.texture : 0;
        in.caustics_irradiance = caustics.irradiance;
        if (in.caustics != 0 && own_caustics_shown && settings.caustic_layer_in_view) {
            in.caustic_layer = own_caustics.layer();
            in.lightmaps = &lightmaps;
        }
        in.sky = sky.present() ? sky.id() : 0;  // synced by render()
        if (sky_masked) {
            in.sky_mask = sky_edges->texture();
            in.sky_mask_scale = sky_edges->scale();
        }
        in.black = black.id();
        // With anti-aliasing the sum goes to the composed target, which the edge pass reads.
        composite.run(targets,
                      anti_aliasing ? targets.composed_target.id() : targets.frame_target.id(),
                      camera, in);
    }

    void render(const FrameCamera& camera, double now_seconds) {
        const gl::StateGuard guard;
        const GLboolean seamless = glIsEnabled(GL_TEXTURE_CUBE_MAP_SEAMLESS);
        ++frame;
        counters.frames = frame;
        timer.begin_frame(frame);
        const lighting::FeaturePlan& plan = lighting.plan();
        const bool specular_pass = plan.specular() && settings.specular_faces_per_frame > 0;

        build_draw_list(registry, lighting, meshes, frame, specular_pass, settings.gpu_skinning,
                        draws);
        track_changes();
        const std::vector<FrameLight> lights =
            plan.direct() || plan.shadows() ? collect_lights(registry) : std::vector<FrameLight>{};
        counters.lights = lights.size();

        glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
        glDisable(GL_CULL_FACE);  // meshes may be single sheets seen from either side
        glDisable(GL_BLEND);
        glDisable(GL_SCISSOR_TEST);
        glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);

        counters.shadow_maps_drawn = 0;
        if (plan.shadows() && !lights.empty()) {
            timer.begin(RenderPass::Shadows);
            glEnable(GL_DEPTH_TEST);
            glDepthFunc(GL_LESS);
            glDepthMask(GL_TRUE);
            shadow_program.use();
            counters.shadow_maps_drawn = shadows.update(lights, draws, shadow_program);
            glDisable(GL_DEPTH_TEST);
            timer.end(RenderPass::Shadows);
        } else {
            shadows.clear();
        }
        counters.shadow_maps = shadows.count();
        counters.shadow_map_renders += counters.shadow_maps_drawn;
        glBindVertexArray(fullscreen.id());

        timer.begin(RenderPass::GBuffer);
        gbuffer_pass(camera);
        timer.end(RenderPass::GBuffer);
        glBindVertexArray(fullscreen.id());

        const bool direct = plan.direct() && !lights.empty() && terms.direct;
        if (direct) {
            const SplitLights split = split_soft(lights, shadows, settings.soft_shadows);
            counters.soft_lights = split.soft.size();
            timer.begin(RenderPass::Direct);
            direct_pass(split.hard);
            timer.end(RenderPass::Direct);
            if (!split.soft.empty()) {
                timer.begin(RenderPass::SoftShadows);
                if (!soft_shadows) {
                    soft_shadows.emplace(shader_library);
                }
                soft_shadows->draw(split.soft, batches, shadows, targets, camera,
                                   settings.filtered_shadows);
                timer.end(RenderPass::SoftShadows);
            }
        } else {
            counters.soft_lights = 0;
            clear_colour(targets.direct_target.id());
        }

        lightmaps.sync(lighting.maps().iim_pages());
        counters.page_uploads = lightmaps.uploads();
        counters.texels_uploaded = lightmaps.texels_uploaded();
        probes.sync(lighting.irradiance_probes());
        counters.probe_uploads = probes.uploads();
        const bool indirect = (!lightmaps.empty() || !probes.empty()) && terms.indirect;
        if (indirect) {
            timer.begin(RenderPass::Indirect);
            indirect_pass(camera, now_seconds);
            timer.end(RenderPass::Indirect);
        } else {
            clear_colour(targets.indirect_target.id());
        }

        // The sky behind the cube maps' faces and the frame: a new one redraws the faces.
        const std::uint64_t sky_before = sky.changes();
        const bool sky_on = sky.sync(lighting.maps().aim());
        const bool sky_changed = sky.changes() != sky_before;
        bool specular = false;
        const glm::ivec2 viewport(settings.width, settings.height);
        own_caustics.sync_pass(settings.caustics, lighting, viewport);
        // The caustic layer, for the cube maps' faces and, by default, the camera; its redraw is
        // timed with the faces when there are any.
        const bool caustic_layer =
            terms.caustics && (specular_pass || settings.caustic_layer_in_view);
        if (specular_pass) {
            timer.begin(RenderPass::Specular);
            const bool caustics_changed = own_caustics.sync_layer(caustic_layer, lighting);
            const bool changed =
                counters.shadow_maps_drawn > 0 || lights.size() != previous_light_count ||
                lightmaps.uploads() != previous_page_uploads || sky_changed || caustics_changed;
            specular = cube_maps.render(
                draws, lights, shadows, batches, lightmaps, own_caustics.layer(), targets, camera,
                sky_on ? sky.id() : 0, now_seconds, changed, terms.specular);
            timer.end(RenderPass::Specular);
        } else {
            cube_maps.clear();
            own_caustics.sync_layer(caustic_layer, lighting);
        }
        if (!specular) {
            clear_colour(targets.specular_target.id());
        }
        previous_light_count = lights.size();
        previous_page_uploads = lightmaps.uploads();
        counters.specular_cube_maps = cube_maps.count();
        counters.specular_faces = cube_maps.faces_rendered();
        counters.draws_over_fill_budget =
            shadows.skipped_casters() + cube_maps.skipped_draws() + gbuffer_skipped;
        const CausticInput external = caustics;
        own_caustics_shown = !caustic_stage && caustics.texture == 0 && own_caustics.has_pass();
        if (terms.caustics && (caustic_stage || own_caustics_shown)) {
            // The stage draws with its own state and timers: outside the composite's query.
            caustics = caustic_stage
                           ? caustic_stage(camera, targets.depth.id())
                           : own_caustics.render(camera, viewport, targets.depth.id(), lighting);
            glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
            glDisable(GL_DEPTH_TEST);
            glDisable(GL_BLEND);
            glDisable(GL_CULL_FACE);
            glDisable(GL_SCISSOR_TEST);
        }
        sky_masked = false;
        if (sky_on && settings.sky_edge_coverage) {
            if (!sky_edges) {
                sky_edges.emplace(shader_library);
            }
            timer.begin(RenderPass::SkyEdges);
            sky_masked = sky_edges->render(draws, camera.projection * camera.view, targets.width,
                                           targets.height);
            timer.end(RenderPass::SkyEdges);
        } else {
            sky_edges.reset();  // no sky, no mask
        }
        glBindVertexArray(fullscreen.id());

        timer.begin(RenderPass::Composite);
        composite_pass(camera, direct, indirect, specular);
        timer.end(RenderPass::Composite);
        if (anti_aliasing) {
            timer.begin(RenderPass::AntiAliasing);
            anti_aliasing->run(targets, sky_masked);
            timer.end(RenderPass::AntiAliasing);
        }
        if (!caustic_stage) {
            caustics = external;  // the own pass's texture is not an external term
        }

        timer.collect(timings, settings.wait_for_timings);
        meshes.evict(frame);
        counters.meshes_cached = meshes.size();
        counters.mesh_uploads = meshes.uploads();
        counters.joint_matrices = draws.joints.size();
        if (seamless == GL_FALSE) {
            glDisable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
        }
        gl::check_error("FrameRenderer::render");
    }
};

FrameRenderer::FrameRenderer(ecs::Registry& registry, const lighting::LightingSystem& lighting,
                             FrameSettings settings)
    : FrameRenderer(registry, lighting, settings, ShaderLibrary()) {}

FrameRenderer::FrameRenderer(ecs::Registry& registry, const lighting::LightingSystem& lighting,
                             FrameSettings settings, const ShaderLibrary& shaders) {
    validate(settings);
    impl_ = std::make_unique<Impl>(registry, lighting, settings, shaders);
}

FrameRenderer::~FrameRenderer() = default;

const FrameTimings& FrameRenderer::render(const FrameCamera& camera, double now_seconds) {
    impl_->render(camera, now_seconds);
    return impl_->timings;
}

void FrameRenderer::set_terms(const FrameTerms& terms) {
    impl_->terms = terms;
}
const FrameTerms& FrameRenderer::terms() const {
    return impl_->terms;
}
void FrameRenderer::set_caustics(const CausticInput& caustics) {
    impl_->caustics = caustics;
}
void FrameRenderer::set_caustic_stage(CausticStage stage) {
    impl_->caustic_stage = std::move(stage);
}

void FrameRenderer::resize(int width, int height) {
    FrameSettings settings = impl_->settings;
    settings.width = width;
    settings.height = height;
    validate(settings);
    impl_->targets = FrameTargets(width, height, settings.anti_aliasing);
    impl_->settings = settings;
    impl_->own_caustics.drop_pass();  // made again at the new size by the next frame
}

lighting::CausticPass* FrameRenderer::caustic_pass() {
    return impl_->own_caustics.pass();
}

GLuint FrameRenderer::frame_texture() const {
    return impl_->targets.frame.id();
}
GLuint FrameRenderer::frame_framebuffer() const {
    return impl_->targets.frame_target.id();
}
GLuint FrameRenderer::depth_texture() const {
    return impl_->targets.depth.id();
}
GLuint FrameRenderer::position_texture() const {
    return impl_->targets.position.id();
}
GLuint FrameRenderer::normal_texture() const {
    return impl_->targets.normal.id();
}
GLuint FrameRenderer::lightmap_texture() const {
    return impl_->targets.lightmap.id();
}

Image FrameRenderer::read(FrameImage image) const {
    const FrameTargets& t = impl_->targets;
    GLint previous = 0;
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &previous);
    // A read-back is a synchronisation point anyway; finishing first also works around
    // llvmpipe (LLVM 15), seen in the tests to return a target's previous contents now and then
    // when it is read right after the frame that drew it.
    glFinish();
    Image result;
    switch (image) {
        case FrameImage::Frame:
            result = gl::read_pixels(t.frame_target.id(), GL_COLOR_ATTACHMENT0, t.width, t.height);
            break;
        case FrameImage::Direct:
            result = gl::read_pixels(t.direct_target.id(), GL_COLOR_ATTACHMENT0, t.width, t.height);
            break;
        case FrameImage::Indirect:
            result =
                gl::read_pixels(t.indirect_target.id(), GL_COLOR_ATTACHMENT0, t.width, t.height);
            break;
        case FrameImage::Specular:
            result =
                gl::read_pixels(t.specular_target.id(), GL_COLOR_ATTACHMENT0, t.width, t.height);
            break;
        case FrameImage::Albedo:
            result = gl::read_pixels(t.gbuffer.id(), GL_COLOR_ATTACHMENT0, t.width, t.height);
            break;
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(previous));
    return result;
}

const FrameTimings& FrameRenderer::timings() const {
    return impl_->timings;
}
const FrameCounters& FrameRenderer::counters() const {
    return impl_->counters;
}
const FrameSettings& FrameRenderer::settings() const {
    return impl_->settings;
}
std::size_t FrameRenderer::shadow_map_count() const {
    return impl_->shadows.count();
}

}  // namespace luxel::renderer
