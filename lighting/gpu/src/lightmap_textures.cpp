#include "luxel/lighting/gpu/lightmap_textures.hpp"

#include <algorithm>

#include "luxel/runtime/texture_sampling.hpp"

namespace luxel::lighting {
namespace {

gl::Texture make_array(GLenum format, int size, int layers) {
    gl::Texture texture = gl::Texture::create(GL_TEXTURE_2D_ARRAY);
    const GLuint id = texture.id();
    glTextureStorage3D(id, 1, format, size, size, layers);
    // texelFetch only: the blend must happen per texel before any filtering.
    gl::set_sampling(id, gl::Sampling::Exact);
    return texture;
}

}  // namespace

bool LightmapTextures::needs_allocation(std::span<const IimPage> pages) const {
    if (static_cast<int>(pages.size()) != layers_) {
        return true;
    }
    for (std::size_t i = 0; i < pages.size(); ++i) {
        if (pages[i].current.size != uploaded_[i].size) {
            return true;
        }
    }
    return false;
}

void LightmapTextures::allocate(std::span<const IimPage> pages) {
    layers_ = static_cast<int>(pages.size());
    layer_size_ = 1;
    std::vector<std::int32_t> sizes;
    for (const IimPage& page : pages) {
        layer_size_ = std::max(layer_size_, page.current.size);
        sizes.push_back(page.current.size);
    }
    uploaded_.assign(pages.size(), PageState{});
    for (std::size_t i = 0; i < pages.size(); ++i) {
        uploaded_[i].size = pages[i].current.size;
    }
    if (layers_ == 0) {
        previous_.reset();
        current_.reset();
        fades_.reset();
        page_sizes_.reset();
        return;
    }
    previous_ = make_array(GL_RGB32F, layer_size_, layers_);
    current_ = make_array(GL_RGB32F, layer_size_, layers_);
    fades_ = make_array(GL_RG32F, layer_size_, layers_);
    page_sizes_ = gl::Buffer::create(sizes.size() * sizeof(std::int32_t), sizes.data(), 0);
    gl::check_error("LightmapTextures allocate");
}

void LightmapTextures::upload_rect(const IimPage& page, int layer, int x, int y, int width,
                                   int height) {
    const int size = page.current.size;
    const std::size_t first =
        static_cast<std::size_t>(y) * static_cast<std::size_t>(size) + static_cast<std::size_t>(x);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, size);
    glTextureSubImage3D(previous_.id(), 0, x, y, layer, width, height, 1, GL_RGB, GL_FLOAT,
                        page.previous.texels.data() + first);
    glTextureSubImage3D(current_.id(), 0, x, y, layer, width, height, 1, GL_RGB, GL_FLOAT,
                        page.current.texels.data() + first);
    glTextureSubImage3D(fades_.id(), 0, x, y, layer, width, height, 1, GL_RG, GL_FLOAT,
                        page.fades.data() + first);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    gl::check_error("LightmapTextures upload");
    ++uploads_;
    texels_uploaded_ += static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
}

bool LightmapTextures::upload_changed(const IimPage& page, int layer) {
    PageState& state = uploaded_[static_cast<std::size_t>(layer)];
    const int size = page.current.size;
    if (size <= 0 || page.previous.size != size ||
        page.fades.size() != page.current.texels.size()) {
        return false;  // a malformed page: nothing sensible to upload
    }
    const void* storage = page.current.texels.data();
    const bool first_time = state.storage != storage;
    if (!first_time && state.version == page.current.version) {
        return false;
    }
    const PageChanges changes = page.current.changes_since(state.version);
    const scene::TexelRect dirty = changes.rect;
    if (first_time || changes.everything) {
        // New storage, or more changes than the page's log remembers: all of it.
        upload_rect(page, layer, 0, 0, size, size);
    } else {
        const int x0 = std::clamp(dirty.x, 0, size);
        const int y0 = std::clamp(dirty.y, 0, size);
        const int x1 = std::clamp(dirty.x + dirty.width, 0, size);
        const int y1 = std::clamp(dirty.y + dirty.height, 0, size);
        if (x1 > x0 && y1 > y0) {
            upload_rect(page, layer, x0, y0, x1 - x0, y1 - y0);
        }
    }
    state.storage = storage;
    state.version = page.current.version;
    return true;
}

void LightmapTextures::bind() const {
    glBindTextureUnit(12, previous_.id());
    glBindTextureUnit(13, current_.id());
    glBindTextureUnit(14, fades_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, empty() ? no_pages_.id() : page_sizes_.id());
}

void LightmapTextures::sync(std::span<const IimPage> pages) {
    if (needs_allocation(pages)) {
        allocate(pages);
    }
    for (std::size_t i = 0; i < pages.size(); ++i) {
        upload_changed(pages[i], static_cast<int>(i));
    }
}

}  // namespace luxel::lighting
