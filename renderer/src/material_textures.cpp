#include "material_textures.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <string>

#include "luxel/runtime/error.hpp"
#include "luxel/scene/image_decode.hpp"

namespace luxel::renderer {
namespace {

// EXT/ARB_texture_filter_anisotropic (core in GL 4.6): the loader is generated for GL 4.5 core
// without the extension, so its two enums are spelled out here (same values in EXT, ARB and
// 4.6).
constexpr GLenum kTextureMaxAnisotropy = 0x84FE;
constexpr GLenum kMaxTextureMaxAnisotropy = 0x84FF;
// More than 16 taps buys nothing visible on a base-colour texture and costs bandwidth.
constexpr float kAnisotropyCap = 16.0f;
/// Added to every material texture's level of detail (why: at the upload).
constexpr float kLodBias = -0.5f;

bool has_extension(const char* wanted) {
    GLint count = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &count);
    for (GLint i = 0; i < count; ++i) {
        const auto* name =
            reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, static_cast<GLuint>(i)));
        if (name != nullptr && std::strcmp(name, wanted) == 0) {
            return true;
        }
    }
    return false;
}

/// Tightly packed client-memory uploads for its lifetime (no pixel-unpack buffer, alignment
/// 4, no row length or skips), restoring whatever the application had set afterwards.
class TightUnpack {
  public:
    TightUnpack() {
        for (std::size_t i = 0; i < kParameters.size(); ++i) {
            glGetIntegerv(kParameters[i], &saved_[i]);
        }
        glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &buffer_);
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
        // RGBA8 rows are 4-byte aligned whatever the width.
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        for (std::size_t i = 1; i < kParameters.size(); ++i) {
            glPixelStorei(kParameters[i], 0);
        }
    }
    ~TightUnpack() {
        for (std::size_t i = 0; i < kParameters.size(); ++i) {
            glPixelStorei(kParameters[i], saved_[i]);
        }
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, static_cast<GLuint>(buffer_));
    }
    TightUnpack(const TightUnpack&) = delete;
    TightUnpack& operator=(const TightUnpack&) = delete;

  private:
    static constexpr std::array<GLenum, 4> kParameters = {
        GL_UNPACK_ALIGNMENT, GL_UNPACK_ROW_LENGTH, GL_UNPACK_SKIP_PIXELS, GL_UNPACK_SKIP_ROWS};
    std::array<GLint, 4> saved_{};
    GLint buffer_ = 0;
};

/// Levels of a full mip chain down to 1x1.
int mip_levels(int width, int height) {
    int levels = 1;
    for (int edge = std::max(width, height); edge > 1; edge /= 2) {
        ++levels;
    }
    return levels;
}

}  // namespace

float MaterialTextures::anisotropy() {
    if (anisotropy_ < 0.0f) {
        anisotropy_ = 0.0f;
        if (has_extension("GL_EXT_texture_filter_anisotropic") ||
            has_extension("GL_ARB_texture_filter_anisotropic")) {
            float max_anisotropy = 0.0f;
            glGetFloatv(kMaxTextureMaxAnisotropy, &max_anisotropy);
            anisotropy_ = std::min(max_anisotropy, kAnisotropyCap);
        }
        gl::check_error("MaterialTextures anisotropy query");
    }
    return anisotropy_;
}

std::shared_ptr<const gl::Texture> MaterialTextures::get(
    const std::shared_ptr<const scene::Scene>& scene, int index) {
    const auto key = std::make_pair(scene.get(), index);
    if (const auto found = textures_.find(key); found != textures_.end()) {
        return found->second.texture;
    }
    if (!scene || index < 0 || static_cast<std::size_t>(index) >= scene->images.size()) {
        throw Error("base-colour texture: image " + std::to_string(index) +
                    " is out of range (the scene has " +
                    std::to_string(scene ? scene->images.size() : 0) + " images)");
    }
    const scene::Image& image = scene->images[static_cast<std::size_t>(index)];
    // Decoded when first drawn, long after loading: the scene names its file.
    scene::DecodedImage decoded;
    try {
        decoded = scene::decode_image(image, index);
    } catch (const Error& e) {
        throw Error(scene->in_file(std::string("base-colour texture: ") + e.what()));
    }
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    if (decoded.width > max_size || decoded.height > max_size) {
        throw Error(
            scene->in_file(scene::image_label(image, index) + ": size " +
                           std::to_string(decoded.width) + "x" + std::to_string(decoded.height) +
                           " exceeds this driver's texture limit " + std::to_string(max_size)));
    }
    auto texture = std::make_shared<gl::Texture>(gl::Texture::create_2d(
        GL_SRGB8_ALPHA8, decoded.width, decoded.height, mip_levels(decoded.width, decoded.height)));
    const GLuint id = texture->id();
    {
        const TightUnpack unpack;
        // Row 0 (the image's top) goes to t = 0, where glTF puts v = 0: no flip needed.
        glTextureSubImage2D(id, 0, 0, 0, decoded.width, decoded.height, GL_RGBA, GL_UNSIGNED_BYTE,
                            decoded.rgba.data());
    }
    glGenerateTextureMipmap(id);
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_REPEAT);
    if (const float aniso = anisotropy(); aniso > 1.0f) {
        glTextureParameterf(id, kTextureMaxAnisotropy, aniso);
    }
    // GL's level of detail follows the longer side of a pixel's footprint, so trilinear
    // filtering blurs a texture seen at about one texel a pixel by a blend with the next level:
    // an emissive sign's edges against luxel-ref's box-filtered pixels (256 samples each, the
    // texture read at every hit) read 8.02% relRMSE with no bias and 5.67% with -0.25, -0.5 or
    // -1 (docs/RESULTS.md, "Emissive textures"). -0.5, the usual choice, keeps half a level of
    // the filter's margin against shimmering where a texture is strongly minified.
    glTextureParameterf(id, GL_TEXTURE_LOD_BIAS, kLodBias);
    gl::check_error("MaterialTextures upload");
    ++uploads_;
    std::shared_ptr<const gl::Texture> shared = std::move(texture);
    textures_.emplace(key, Entry{scene, shared});
    return shared;
}

GLuint MaterialTextures::white() {
    if (!white_) {
        white_ = gl::Texture::create_2d(GL_SRGB8_ALPHA8, 1, 1);
        const std::array<std::uint8_t, 4> opaque_white = {255, 255, 255, 255};
        const TightUnpack unpack;
        glTextureSubImage2D(white_.id(), 0, 0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE,
                            opaque_white.data());
        gl::check_error("MaterialTextures white");
    }
    return white_.id();
}

void MaterialTextures::evict() {
    std::erase_if(textures_,
                  [](const auto& entry) { return entry.second.texture.use_count() == 1; });
}

}  // namespace luxel::renderer
