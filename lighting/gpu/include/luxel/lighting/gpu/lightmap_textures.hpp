#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "luxel/lighting/core/iim_page.hpp"
#include "luxel/runtime/gl_objects.hpp"

namespace luxel::lighting {

/// The IIM pages on the GPU, for shaders/render/indirect.frag: three 2D array textures with
/// one layer per page, sized for the largest page (smaller pages sit in their layer's corner):
/// `previous` and `current` (RGB32F) and `fades` (RG32F: the second each texel's fade
/// began and how many seconds it lasts, IimFade). The shader blends per texel and filters
/// bilinearly itself, so nothing here is filtered. A buffer of page sizes lets it clamp lookups to
/// each page.
///
/// Uploads: every page once, then, for a page whose `current.version` changed, the rectangle
/// that changed since the version this copy last uploaded (RadiancePage::changes_since) in
/// all three arrays with glTextureSubImage3D,
/// reading straight from the page's rows (GL_UNPACK_ROW_LENGTH) without a copy. The
/// arrays are reallocated when the page count or the largest size changes.
class LightmapTextures {
  public:
    /// Uploads what changed in `pages` since this copy last read them. The pages are only
    /// read: every copy (the sandbox's renderer, luxel-bench's frame view) keeps its own
    /// versions, so each uploads exactly what it has not seen.
    void sync(std::span<const IimPage> pages);

    [[nodiscard]] bool empty() const { return layers_ == 0; }
    /// Binds the arrays to texture units 12-14 and the page sizes to storage block 1
    /// (shaders/render/iim.glsl). Without pages, a one-entry size table of 0 makes every
    /// lookup read nothing.
    void bind() const;
    [[nodiscard]] GLuint previous() const { return previous_.id(); }
    [[nodiscard]] GLuint current() const { return current_.id(); }
    [[nodiscard]] GLuint fades() const { return fades_.id(); }
    [[nodiscard]] GLuint page_sizes() const { return page_sizes_.id(); }
    [[nodiscard]] std::uint64_t uploads() const { return uploads_; }
    [[nodiscard]] std::uint64_t texels_uploaded() const { return texels_uploaded_; }

  private:
    struct PageState {
        int size = 0;
        std::uint64_t version = 0;
        const void* storage = nullptr;
    };

    /// Whether the arrays must be reallocated for `pages`.
    [[nodiscard]] bool needs_allocation(std::span<const IimPage> pages) const;
    void allocate(std::span<const IimPage> pages);
    /// Uploads what changed in page `layer` since `uploaded_`'s version; returns whether it did.
    bool upload_changed(const IimPage& page, int layer);
    void upload_rect(const IimPage& page, int layer, int x, int y, int width, int height);

    gl::Texture previous_;
    gl::Texture current_;
    gl::Texture fades_;
    gl::Buffer page_sizes_;
    static constexpr std::int32_t kNoPageSize = 0;
    gl::Buffer no_pages_ = gl::Buffer::create(sizeof(std::int32_t), &kNoPageSize, 0);
    int layers_ = 0;
    int layer_size_ = 0;
    std::vector<PageState> uploaded_;
    std::uint64_t uploads_ = 0;
    std::uint64_t texels_uploaded_ = 0;
};

}  // namespace luxel::lighting
