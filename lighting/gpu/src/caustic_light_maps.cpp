#include "luxel/lighting/gpu/caustic_light_maps.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <span>

#include "caustic_photon_buffer.hpp"
#include "luxel/lighting/gpu/caustic_pass.hpp"
#include "luxel/runtime/gl_state_guard.hpp"
#include "luxel/runtime/shader_library.hpp"
#include "luxel/runtime/texture_sampling.hpp"

#include "caustics/caustic_interface.h"

namespace luxel::lighting {
namespace {

constexpr GLuint kPhotonsBinding = CAUSTIC_PHOTONS_BINDING;
constexpr GLuint kSurfacesBinding = CAUSTIC_LIGHT_MAP_SURFACES_BINDING;

}  // namespace

CausticLightMaps::CausticLightMaps(const ShaderLibrary& shaders)
    : program_(shaders.build({{ShaderStage::Vertex, "caustics/light_map_splat.vert"},
                              {ShaderStage::Geometry, "caustics/light_map_splat.geom"},
                              {ShaderStage::Fragment, "caustics/light_map_splat.frag"}})) {}

std::vector<glm::vec4> CausticLightMaps::surface_table(const IlluminationMaps& maps) {
    const std::span<const MapSurface> surfaces = maps.surfaces();
    const std::vector<std::int32_t>& surface_page = maps.aim().surface_page;
    const std::span<const IimPage> pages = maps.iim_pages();
    std::vector<glm::vec4> table(surfaces.size(), glm::vec4(-1.0f, 0.0f, 0.0f, 0.0f));
    for (std::size_t s = 0; s < surfaces.size(); ++s) {
        const std::int32_t page = s < surface_page.size() ? surface_page[s] : -1;
        const double metres = surfaces[s].world_metres_per_texel;
        const double area = metres * metres;
        // A surface without a page, or scaled to nothing, bins no photon (its texel area is
        // the divisor).
        if (page < 0 || static_cast<std::size_t>(page) >= pages.size() || !(area > 0.0)) {
            continue;
        }
        const float inverse_area = static_cast<float>(1.0 / area);
        if (!(inverse_area < std::numeric_limits<float>::max())) {
            continue;
        }
        table[s] = glm::vec4(static_cast<float>(page),
                             static_cast<float>(pages[static_cast<std::size_t>(page)].current.size),
                             inverse_area, 0.0f);
    }
    return table;
}

void CausticLightMaps::allocate(const IlluminationMaps& maps) {
    const std::span<const IimPage> pages = maps.iim_pages();
    page_sizes_.clear();
    layer_size_ = 0;
    for (const IimPage& page : pages) {
        page_sizes_.push_back(page.current.size);
        layer_size_ = std::max(layer_size_, page.current.size);
    }
    layers_ = layer_size_ > 0 ? static_cast<int>(pages.size()) : 0;
    texture_.reset();
    framebuffer_.reset();
    if (layers_ == 0) {
        layer_size_ = 0;
        return;
    }
    texture_ = gl::Texture::create(GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(texture_.id(), 1, GL_RGBA32F, layer_size_, layer_size_, layers_);
    // Read texel by texel (shaders/render/caustic_light_map.glsl).
    gl::set_sampling(texture_.id(), gl::Sampling::Exact);
    framebuffer_ = gl::Framebuffer::create();
    // The whole array: a layered attachment, whose layer each point picks (gl_Layer).
    framebuffer_.attach(GL_COLOR_ATTACHMENT0, texture_);
    glNamedFramebufferDrawBuffer(framebuffer_.id(), GL_COLOR_ATTACHMENT0);
    framebuffer_.check_complete("CausticLightMaps");
    gl::check_error("CausticLightMaps allocate");
}

void CausticLightMaps::draw(const CausticPass& caustics) {
    const std::array<float, 4> zero = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearTexImage(texture_.id(), 0, GL_RGBA, GL_FLOAT, zero.data());
    const CausticPhotonBuffer& photons = caustics.photon_buffer();
    if (photons.photon_count() == 0 || table_.empty()) {
        return;
    }
    const gl::StateGuard guard;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer_.id());
    glViewport(0, 0, layer_size_, layer_size_);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_PROGRAM_POINT_SIZE);
    glPointSize(1.0f);  // one texel: the point covers the texel its centre is in
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPhotonsBinding, photons.buffer());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSurfacesBinding, surfaces_.id());
    program_.use();
    program_.set("u_layer_size", static_cast<float>(layer_size_));
    glBindVertexArray(empty_vertex_array_.id());
    glMultiDrawArrays(GL_POINTS, photons.firsts().data(), photons.counts().data(),
                      static_cast<GLsizei>(photons.counts().size()));
    gl::check_error("CausticLightMaps draw");
}

void CausticLightMaps::bind() const {
    if (!empty()) {
        glBindTextureUnit(kTextureUnit, texture_.id());
    }
}

bool CausticLightMaps::sync(const CausticPass& caustics, const IlluminationMaps& maps) {
    bool redraw = !drawn_;
    const std::span<const IimPage> pages = maps.iim_pages();
    bool same_pages = pages.size() == page_sizes_.size();
    for (std::size_t i = 0; same_pages && i < pages.size(); ++i) {
        same_pages = pages[i].current.size == page_sizes_[i];
    }
    if (!same_pages) {
        allocate(maps);
        redraw = true;
    }
    std::vector<glm::vec4> table = surface_table(maps);
    if (table != table_) {
        table_ = std::move(table);
        surfaces_ = table_.empty()
                        ? gl::Buffer{}
                        : gl::Buffer::create(table_.size() * sizeof(glm::vec4), table_.data(), 0);
        redraw = true;
    }
    const CausticPhotonBuffer& photons = caustics.photon_buffer();
    if (photons.slices_uploaded() != slices_seen_ || photons.buffer() != buffer_seen_) {
        slices_seen_ = photons.slices_uploaded();
        buffer_seen_ = photons.buffer();
        redraw = true;
    }
    if (!redraw || layers_ == 0) {
        return false;
    }
    draw(caustics);
    drawn_ = true;
    ++redraws_;
    return true;
}

}  // namespace luxel::lighting
