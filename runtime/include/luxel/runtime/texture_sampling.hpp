#pragma once

#include "luxel/runtime/gl.hpp"

namespace luxel::gl {

/// How a texture is read. Every axis clamps to its edge: of luxel's textures only the material
/// textures (repeat, mipmaps, anisotropy) and the sky's azimuth (repeat) wrap, and they set
/// their own parameters.
enum class Sampling {
    Filtered,  ///< bilinear between texels (light-map pages, probe atlases, cube maps)
    Exact,     ///< one texel, no filtering (texelFetch targets, raw shadow depths)
};

/// Sets the minification and magnification filter and the S, T and R wraps of `texture`.
void set_sampling(GLuint texture, Sampling sampling);

}  // namespace luxel::gl
