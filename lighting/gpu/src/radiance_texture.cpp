#include "radiance_texture.hpp"

#include <algorithm>

#include "luxel/runtime/texture_sampling.hpp"

namespace luxel::lighting {

void RadianceTexture::allocate(const RadianceAtlas& atlas) {
    layer_size_ = 1;
    for (const RadiancePage& page : atlas.pages) {
        layer_size_ = std::max(layer_size_, page.size);
    }
    // At least one layer, so the sampler is always complete even with no pages.
    const auto layers = static_cast<GLsizei>(std::max<std::size_t>(atlas.pages.size(), 1));
    texture_ = gl::Texture::create(GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(texture_.id(), 1, GL_RGB32F, layer_size_, layer_size_, layers);
    gl::set_sampling(texture_.id(), gl::Sampling::Filtered);
    // Unused corners of smaller pages and the empty layer (no page yet) read as black.
    const float zero[3] = {0.0f, 0.0f, 0.0f};
    glClearTexImage(texture_.id(), 0, GL_RGB, GL_FLOAT, zero);
    gl::check_error("RadianceTexture allocate");
    uploaded_.assign(atlas.pages.size(), PageState{});
}

void RadianceTexture::upload_page(const RadiancePage& page, int layer) {
    if (page.size > 0 && page.texels.size() == static_cast<std::size_t>(page.size) *
                                                   static_cast<std::size_t>(page.size)) {
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
        glTextureSubImage3D(texture_.id(), 0, 0, 0, layer, page.size, page.size, 1, GL_RGB,
                            GL_FLOAT, page.texels.data());
        gl::check_error("RadianceTexture upload");
    }
    uploaded_[static_cast<std::size_t>(layer)] = {page.size, page.version, page.texels.data()};
    ++page_uploads_;
}

void RadianceTexture::sync(const RadianceAtlas& atlas) {
    bool reallocate = !texture_ || uploaded_.size() != atlas.pages.size();
    for (std::size_t i = 0; !reallocate && i < atlas.pages.size(); ++i) {
        reallocate = uploaded_[i].size != atlas.pages[i].size;
    }
    if (reallocate) {
        allocate(atlas);
    }
    for (std::size_t i = 0; i < atlas.pages.size(); ++i) {
        const RadiancePage& page = atlas.pages[i];
        const PageState& state = uploaded_[i];
        if (reallocate || state.version != page.version || state.storage != page.texels.data()) {
            upload_page(page, static_cast<int>(i));
        }
    }

    // Two vec4 per surface: its page (layer or -1, page size / layer size, the UV clamp
    // range), then the radiance its front emits (RadianceAtlas::surface_emission).
    std::vector<glm::vec4> table;
    const std::size_t surfaces = atlas.surface_page.size();
    table.reserve(2 * std::max<std::size_t>(surfaces, 1));
    for (std::size_t s = 0; s < surfaces; ++s) {
        const std::int32_t page = atlas.surface_page[s];
        const glm::vec3 emission =
            s < atlas.surface_emission.size() ? atlas.surface_emission[s] : glm::vec3(0.0f);
        if (page < 0 || static_cast<std::size_t>(page) >= atlas.pages.size() ||
            atlas.pages[static_cast<std::size_t>(page)].size <= 0) {
            table.emplace_back(-1.0f, 0.0f, 0.0f, 0.0f);
        } else {
            const auto size = static_cast<float>(atlas.pages[static_cast<std::size_t>(page)].size);
            // Clamping the UV to the outermost texel centres keeps both bilinear taps on the
            // page (RadiancePage::sample clamps the same way); the scale then maps the page's
            // UV into its corner of the larger layer.
            table.emplace_back(static_cast<float>(page), size / static_cast<float>(layer_size_),
                               0.5f / size, (size - 0.5f) / size);
        }
        table.emplace_back(emission, 0.0f);
    }
    if (table.empty()) {
        table.emplace_back(-1.0f, 0.0f, 0.0f, 0.0f);
        table.emplace_back(0.0f);
    }
    if (!surface_table_ || table != table_) {
        // Recreated when the surface count changes: the shader bounds its lookups by the
        // buffer's length.
        if (surface_table_.size() != table.size() * sizeof(glm::vec4)) {
            surface_table_ = gl::Buffer::create(table.size() * sizeof(glm::vec4), table.data());
        } else {
            surface_table_.update(0, table.size() * sizeof(glm::vec4), table.data());
        }
        table_ = std::move(table);
    }
}

}  // namespace luxel::lighting
