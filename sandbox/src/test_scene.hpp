#pragma once

#include <glm/glm.hpp>

#include "luxel/runtime/gl_objects.hpp"
#include "luxel/runtime/program.hpp"
#include "luxel/runtime/render_target.hpp"
#include "luxel/runtime/shader_library.hpp"

namespace luxel::sandbox {

/// The built-in lit test scene the sandbox draws until the game level exists: a 4 m box room
/// (red left wall, green right wall), two blocks, and a 60 W point light under the ceiling,
/// drawn with direct Lambertian lighting only. The camera orbits slowly with time.
class TestScene {
  public:
    explicit TestScene(const ShaderLibrary& shaders);

    /// Draws the scene at `time_seconds` into `target` (linear radiance, RGBA32F).
    void render(const gl::RenderTarget& target, double time_seconds) const;

  private:
    gl::Program program_;
    gl::VertexArray vertex_array_;
    gl::Buffer vertices_;
    int vertex_count_ = 0;
};

}  // namespace luxel::sandbox
