#include "joint_palette.hpp"

#include <algorithm>
#include <limits>

#include "luxel/runtime/error.hpp"

namespace luxel::renderer {

std::int32_t JointPalette::add(const std::vector<glm::mat4>& joints) {
    // The shader indexes with an int: a frame's palette stays below 2^31 matrices (a glTF skin
    // already refuses more joints than its file can hold; this guards their sum).
    if (matrices_.size() + joints.size() >
        static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
        throw Error("JointPalette: more than 2^31 joint matrices in one frame");
    }
    const auto first = static_cast<std::int32_t>(matrices_.size());
    matrices_.insert(matrices_.end(), joints.begin(), joints.end());
    return first;
}

void JointPalette::upload() {
    if (matrices_.empty()) {
        return;
    }
    const std::size_t bytes = matrices_.size() * sizeof(glm::mat4);
    if (buffer_.id() == 0 || buffer_.size() < bytes) {
        buffer_ = gl::Buffer::create(std::max(bytes, 2 * buffer_.size()));
    }
    buffer_.update(0, bytes, matrices_.data());
    bytes_uploaded_ += bytes;
}

}  // namespace luxel::renderer
