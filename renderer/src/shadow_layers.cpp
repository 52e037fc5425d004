#include "shadow_layers.hpp"

#include <algorithm>
#include <utility>

#include "luxel/runtime/texture_sampling.hpp"

namespace luxel::renderer {

ShadowLayers::ShadowLayers(GLenum target, int size) : target_(target), size_(std::max(size, 1)) {}

int ShadowLayers::acquire() {
    const auto free = std::find(used_.begin(), used_.end(), false);
    if (free != used_.end()) {
        *free = true;
        return static_cast<int>(free - used_.begin());
    }
    const int layer = capacity_;
    grow(std::max(1, 2 * capacity_));
    used_[static_cast<std::size_t>(layer)] = true;
    return layer;
}

void ShadowLayers::release(int layer) {
    if (layer < 0 || layer >= capacity_) {
        return;
    }
    used_[static_cast<std::size_t>(layer)] = false;
    if (std::none_of(used_.begin(), used_.end(), [](bool used) { return used; })) {
        texture_ = gl::Texture();
        used_.clear();
        capacity_ = 0;
    }
}

void ShadowLayers::grow(int capacity) {
    gl::Texture texture = gl::Texture::create(target_);
    const GLuint id = texture.id();
    glTextureStorage3D(id, 1, GL_DEPTH_COMPONENT32F, size_, size_, capacity * faces());
    // Raw depths read at texel centres: the shaders compare them themselves
    // (shaders/render/shadow.glsl), so no comparison mode and no filtering.
    gl::set_sampling(id, gl::Sampling::Exact);
    if (capacity_ > 0) {
        glCopyImageSubData(texture_.id(), target_, 0, 0, 0, 0, id, target_, 0, 0, 0, 0, size_,
                           size_, capacity_ * faces());
    }
    gl::check_error("ShadowLayers grow");
    texture_ = std::move(texture);
    capacity_ = capacity;
    used_.resize(static_cast<std::size_t>(capacity), false);
}

}  // namespace luxel::renderer
