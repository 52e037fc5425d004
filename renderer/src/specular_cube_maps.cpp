#include "specular_cube_maps.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <set>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "cube_faces.hpp"
#include "fill_budget.hpp"
#include "luxel/runtime/log.hpp"
#include "luxel/runtime/shader_library.hpp"
#include "luxel/runtime/texture_sampling.hpp"
#include "material_textures.hpp"

namespace luxel::renderer {
namespace {

/// How far a face draws: twice the level's diagonal, so a probe anywhere in it sees all of it.
float face_reach(const DrawList& draws) {
    return std::max(glm::length(draws.bounds.hi - draws.bounds.lo) * 2.0f, 1.0f);
}

}  // namespace

SpecularCubeMaps::SpecularCubeMaps(const ShaderLibrary& shaders, int size, int faces_per_frame)
    : face_program_(shaders.build(
          {{ShaderStage::Vertex, "render/mesh.vert"},
           {ShaderStage::Fragment, "render/cube_map_face.frag"}},
          "#define LIGHTS_PER_BATCH " + std::to_string(LightBatches::kLightsPerBatch) + "\n")),
      sky_program_(shaders.build({{ShaderStage::Vertex, "post/fullscreen.vert"},
                                  {ShaderStage::Fragment, "render/cube_map_sky.frag"}})),
      specular_program_(shaders.build({{ShaderStage::Vertex, "render/mesh.vert"},
                                       {ShaderStage::Fragment, "render/specular.frag"}})),
      size_(std::max(size, 1)),
      faces_per_frame_(std::max(faces_per_frame, 0)) {}

void SpecularCubeMaps::invalidate(const Bounds& /*bounds*/) {
    // Any change may be seen in a mirror, wherever it is: every cube_map refreshes.
    for (auto& [entity, cube_map] : cube_maps_) {
        cube_map.stale_faces = 6;
    }
}

SpecularCubeMaps::CubeMap SpecularCubeMaps::allocate() const {
    CubeMap cube_map;
    cube_map.cube = gl::Texture::create(GL_TEXTURE_CUBE_MAP);
    // Radiance: 32-bit like every radiance target (half floats overflow at 65,504).
    glTextureStorage2D(cube_map.cube.id(), 1, GL_RGBA32F, size_, size_);
    gl::set_sampling(cube_map.cube.id(), gl::Sampling::Filtered);
    cube_map.depth = gl::Renderbuffer::create(GL_DEPTH_COMPONENT32F, size_, size_);
    cube_map.framebuffer = gl::Framebuffer::create();
    cube_map.framebuffer.attach(GL_DEPTH_ATTACHMENT, cube_map.depth);
    glNamedFramebufferDrawBuffer(cube_map.framebuffer.id(), GL_COLOR_ATTACHMENT0);
    gl::check_error("SpecularCubeMaps allocate");
    return cube_map;
}

void SpecularCubeMaps::render_face(CubeMap& cube_map, int face, const DrawList& draws, GLuint sky) {
    const GLuint fbo = cube_map.framebuffer.id();
    glNamedFramebufferTextureLayer(fbo, GL_COLOR_ATTACHMENT0, cube_map.cube.id(), 0, face);
    cube_map.framebuffer.check_complete("specular cube_map face");
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    glViewport(0, 0, size_, size_);
    // No light, and alpha "far": the distance the specular term's parallax correction reads
    // where nothing was drawn (shaders/render/specular.frag).
    const std::array<float, 4> nothing = {0.0f, 0.0f, 0.0f, 1e6f};
    const float far_depth = 1.0f;
    glClearNamedFramebufferfv(fbo, GL_COLOR, 0, nothing.data());
    glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &far_depth);
    const glm::mat4 projection =
        glm::perspective(glm::half_pi<float>(), 1.0f, 0.01f, face_reach(draws));
    const gl::Program& program = face_program_;
    const glm::mat4 view_projection = projection * cube_face_view(cube_map.centre, face);
    if (sky != 0) {
        // The sky first, everywhere, without depth; the level is drawn over it.
        glDisable(GL_DEPTH_TEST);
        sky_program_.use();
        sky_program_.set("u_inverse_view_projection", glm::inverse(view_projection));
        sky_program_.set("u_centre", cube_map.centre);
        glBindTextureUnit(17, sky);
        glBindVertexArray(sky_triangle_.id());
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glEnable(GL_DEPTH_TEST);
        program.use();
    }
    program.set("u_view_projection", view_projection);
    program.set("u_camera", cube_map.centre);
    // The face covers what it sees as a shadow map does: geometry stacked on itself is left
    // out past the budget (fill_budget.hpp says why).
    FillBudget budget(static_cast<double>(size_) * static_cast<double>(size_));
    draw_in_view(
        draws, view_projection, size_, size_, budget,
        // No mirror sees another (or itself): one bounce of specular.
        [](const DrawItem& item) { return !item.specular; },
        [&](const DrawItem& item) { bind_draw_item(program, item); },
        [&](const DrawItem& item, const DrawPrimitive& primitive) {
            cull_as_material(item, primitive.material);
            program.set("u_albedo", primitive.material.albedo);
            glBindTextureUnit(kBaseColorTextureUnit, primitive.material.base_color_texture);
            glBindTextureUnit(kEmissiveTextureUnit, primitive.material.emissive_texture);
            program.set("u_emission", primitive.material.emission);
            program.set("u_lightmap", primitive.material.lightmap);
            draw_primitive(*primitive.range);
        });
    glDisable(GL_CULL_FACE);
    glFrontFace(GL_CCW);
    ++faces_rendered_;
    if (budget.skipped() > 0 && skipped_draws_ == 0) {
        log::warn("a specular cube map face's draws would cover about ", budget.wanted(),
                  " texels of one ", size_, "x", size_, " face (", FillBudget::kLayers,
                  " layers allowed): the level stacks geometry on itself; ", budget.skipped(),
                  " primitives are left out of the reflections");
    }
    skipped_draws_ += budget.skipped();
}

void SpecularCubeMaps::draw_term(const DrawList& draws, const FrameTargets& targets,
                                 const FrameCamera& camera) {
    const GLuint fbo = targets.specular_target.id();
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    glViewport(0, 0, targets.width, targets.height);
    const std::array<float, 4> zero = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearNamedFramebufferfv(fbo, GL_COLOR, 0, zero.data());
    // Over the G-buffer's depth, without writing it: only the object's visible pixels.
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    const gl::Program& program = specular_program_;
    program.use();
    program.set("u_view_projection", camera.projection * camera.view);
    program.set("u_camera", camera.position);
    for (const DrawItem& item : draws.items) {
        const auto found = cube_maps_.find(item.entity);
        if (!item.specular || found == cube_maps_.end()) {
            continue;
        }
        glBindTextureUnit(0, found->second.cube.id());
        program.set("u_probe_centre", found->second.centre);
        program.set("u_probe_reach", face_reach(draws));
        program.set("u_probe_extent", 0.5f * (item.bounds.hi - item.bounds.lo));
        bind_draw_item(program, item);
        for (std::size_t i = item.first; i < item.first + item.count; ++i) {
            const DrawPrimitive& primitive = draws.primitives[i];
            if (primitive.range->index_count == 0 || primitive.material.specular.r <= 0.0f) {
                continue;
            }
            program.set("u_specular", primitive.material.specular);
            program.set("u_ior", primitive.material.ior);
            program.set("u_transmittance", primitive.material.transmittance);
            program.set("u_tint", primitive.material.tint);
            program.set("u_attenuation", primitive.material.attenuation);
            draw_primitive(*primitive.range);
        }
    }
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    glDisable(GL_DEPTH_TEST);
}

bool SpecularCubeMaps::render(const DrawList& draws, const std::vector<FrameLight>& lights,
                              const ShadowMaps& shadows, LightBatches& batches,
                              const lighting::LightmapTextures& lightmaps,
                              const lighting::CausticLightMaps* caustics,
                              const FrameTargets& targets, const FrameCamera& camera, GLuint sky,
                              double now_seconds, bool scene_changed, bool draw_term_now) {
    std::set<ecs::Entity> present;
    for (const DrawItem& item : draws.items) {
        if (!item.specular) {
            continue;
        }
        present.insert(item.entity);
        auto found = cube_maps_.find(item.entity);
        if (found == cube_maps_.end()) {
            found = cube_maps_.emplace(item.entity, allocate()).first;
        }
        CubeMap& cube_map = found->second;
        const glm::vec3 centre = 0.5f * (item.bounds.lo + item.bounds.hi);
        if (centre != cube_map.centre || scene_changed) {
            cube_map.centre = centre;
            cube_map.stale_faces = 6;
        }
    }
    std::erase_if(cube_maps_, [&](const auto& entry) { return !present.contains(entry.first); });
    if (cube_maps_.empty()) {
        return false;
    }

    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    face_program_.use();
    face_program_.set("u_filtered", 1);
    face_program_.set("u_now", static_cast<float>(now_seconds));
    batches.bind(lights, 0, shadows);
    lightmaps.bind();
    const bool caustic_layer = caustics != nullptr && !caustics->empty();
    face_program_.set("u_caustic_layer", caustic_layer ? 1 : 0);
    if (caustic_layer) {
        caustics->bind();
    }
    for (auto& [entity, cube_map] : cube_maps_) {
        // A new cube_map fills every face at once so it never shows black; afterwards the budget
        // holds.
        int budget = cube_map.filled ? faces_per_frame_ : 6;
        cube_map.filled = true;
        while (cube_map.stale_faces > 0 && budget > 0) {
            render_face(cube_map, cube_map.next_face, draws, sky);
            cube_map.next_face = (cube_map.next_face + 1) % 6;
            --cube_map.stale_faces;
            --budget;
        }
    }
    glDisable(GL_DEPTH_TEST);
    if (!draw_term_now) {
        return false;
    }
    draw_term(draws, targets, camera);
    return true;
}

}  // namespace luxel::renderer
