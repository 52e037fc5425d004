#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/runtime/gl_objects.hpp"

namespace luxel::renderer {

/// The shader storage binding of the joint matrices (shaders/render/skinning.glsl).
inline constexpr GLuint kJointMatricesBinding = 20;

/// This frame's joint matrices of every skinned mesh drawn, in one shader storage buffer that
/// the vertex stage reads (shaders/render/skinning.glsl): a new pose costs 64 bytes a joint on
/// the bus instead of 40 a vertex, and the skinned mesh's vertices are uploaded once.
///
/// Filled while the draw list is built, uploaded once a frame; the buffer only grows (by
/// doubling), so a figure that walks every frame reallocates nothing.
class JointPalette {
  public:
    /// Forgets last frame's matrices (keeps the buffer).
    void clear() { matrices_.clear(); }
    /// Appends one mesh's joint matrices; returns the index of its first in the buffer.
    std::int32_t add(const std::vector<glm::mat4>& joints);
    /// Uploads what was added since clear(); nothing when nothing was (no buffer is made for a
    /// frame without skinned meshes).
    void upload();
    [[nodiscard]] GLuint buffer() const { return buffer_.id(); }
    [[nodiscard]] std::size_t size() const { return matrices_.size(); }
    /// Bytes uploaded since construction.
    [[nodiscard]] std::uint64_t bytes_uploaded() const { return bytes_uploaded_; }

  private:
    std::vector<glm::mat4> matrices_;
    gl::Buffer buffer_;
    std::uint64_t bytes_uploaded_ = 0;
};

}  // namespace luxel::renderer
