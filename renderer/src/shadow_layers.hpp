#pragma once

#include <cstddef>
#include <vector>

#include "luxel/runtime/gl.hpp"
#include "luxel/runtime/gl_objects.hpp"

namespace luxel::renderer {

/// One depth texture array holding every shadow map of one shape, a layer per map: a 2D array
/// for the spot and sun maps, a cube-map array for the cube maps. The direct pass reads each
/// array through one sampler, indexed by the layer in the light record: no sampler array
/// indexed per light (which llvmpipe resolved wrongly for some lanes) and no branch per slot
/// (which cost the direct pass 45% on llvmpipe), and two texture units for any number of
/// lights.
///
/// Layers are handed out on demand. The texture is allocated with the first layer, grows by
/// doubling (copying the maps it holds, so none is drawn again), and is freed with the last
/// layer: a level without lights of this shape holds no texture for them.
class ShadowLayers {
  public:
    /// `target` GL_TEXTURE_2D_ARRAY or GL_TEXTURE_CUBE_MAP_ARRAY; `size` texels per edge.
    /// DEPTH_COMPONENT32F, nearest texels, no comparison mode: the shaders compare.
    ShadowLayers(GLenum target, int size);

    /// A free layer, growing the texture when none is left.
    [[nodiscard]] int acquire();
    /// Returns `layer` to the free list; the last one frees the texture.
    void release(int layer);

    /// The array texture; 0 while no layer is held.
    [[nodiscard]] GLuint id() const { return texture_.id(); }
    /// GL layers per map layer: 6 faces for a cube-map array, else 1.
    [[nodiscard]] int faces() const { return target_ == GL_TEXTURE_CUBE_MAP_ARRAY ? 6 : 1; }

  private:
    void grow(int capacity);

    GLenum target_;
    int size_;
    int capacity_ = 0;
    gl::Texture texture_;
    std::vector<bool> used_;
};

}  // namespace luxel::renderer
