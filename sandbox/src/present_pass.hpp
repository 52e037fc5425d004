#pragma once

#include "luxel/runtime/gl_objects.hpp"
#include "luxel/runtime/program.hpp"
#include "luxel/runtime/shader_library.hpp"
#include "luxel/runtime/tone_map.hpp"

namespace luxel::sandbox {

/// Tone-maps an HDR texture into the window's default framebuffer (sRGB, 8-bit). Uses the same
/// curve as write_png so the window and the PNG files look alike.
class PresentPass {
  public:
    explicit PresentPass(const ShaderLibrary& shaders);
    void draw(GLuint hdr_texture, int width, int height, const ToneMapSettings& settings) const;

  private:
    gl::Program program_;
    gl::VertexArray empty_vertex_array_;
};

}  // namespace luxel::sandbox
