#include "luxel/runtime/texture_sampling.hpp"

namespace luxel::gl {

void set_sampling(GLuint texture, Sampling sampling) {
    const GLint filter = sampling == Sampling::Filtered ? GL_LINEAR : GL_NEAREST;
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, filter);
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, filter);
    // R as well: harmless on 2D textures, needed by cube maps and arrays of cube faces.
    glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
}

}  // namespace luxel::gl
