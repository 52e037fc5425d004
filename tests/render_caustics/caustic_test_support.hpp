#pragma once

// Scenes for the caustic pass tests and benchmark: a headless GL context, a scene of flat
// rectangles whose depth texture is ray-cast on the CPU (exact, no rasteriser in the
// reference), photons placed on those rectangles through chosen pixels, and read-backs.

#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/core/caustic_photons.hpp"
#include "luxel/lighting/gpu/caustic_pass.hpp"
#include "luxel/runtime/gl_context.hpp"
#include "luxel/runtime/gl_objects.hpp"

namespace luxel::test {

/// A headless GL 4.5 context (EGL: llvmpipe on the surfaceless platform without a GPU).
[[nodiscard]] std::unique_ptr<GlContext> make_caustic_gl_context();

/// A rectangle centre + s u + t v, s, t in [-1, 1] (u, v: half extents, orthogonal).
struct Rect {
    glm::vec3 centre;
    glm::vec3 u;
    glm::vec3 v;
};

/// A camera at `eye` looking at `target` (+y up unless looking along y).
[[nodiscard]] lighting::CausticCamera look_at(const glm::vec3& eye, const glm::vec3& target,
                                              glm::ivec2 viewport, float vertical_fov = 1.0f);

/// The scene the camera sees: its rectangles, ray-cast through each pixel centre.
class RectScene {
  public:
    RectScene(const lighting::CausticCamera& camera, std::vector<Rect> rects);

    /// The nearest hit through pixel (x, y)'s centre, world space.
    [[nodiscard]] std::optional<glm::vec3> hit(int x, int y) const;
    /// A point through (window x, y) on the nearest rectangle.
    [[nodiscard]] std::optional<glm::vec3> hit_window(const glm::vec2& window) const;
    /// View depth of the surface at a pixel (0 where empty).
    [[nodiscard]] double view_depth(int x, int y) const;
    /// A DEPTH_COMPONENT32F texture of the scene for the camera (GL depth range [-1, 1] mapped
    /// to [0, 1]; 1 where empty).
    [[nodiscard]] const gl::Texture& depth_texture() const { return depth_; }
    [[nodiscard]] const lighting::CausticCamera& camera() const { return camera_; }
    /// World-space area of pixel (x, y) on its surface (exact for a plane: A_facing / |n.p|).
    [[nodiscard]] double pixel_area(int x, int y) const;

  private:
    [[nodiscard]] std::optional<std::pair<glm::vec3, int>> cast(const glm::vec2& window) const;

    lighting::CausticCamera camera_;
    std::vector<Rect> rects_;
    gl::Texture depth_;
};

/// RGBA32F texture contents, row-major from the bottom row.
[[nodiscard]] std::vector<glm::vec4> read_rgba(GLuint texture, glm::ivec2 size);

/// sum over pixels of E * pixel_area (watts), per channel.
[[nodiscard]] glm::dvec3 total_power(const std::vector<glm::vec4>& image, const RectScene& scene);

/// The pass's irradiance for `photons` through a fresh CausticPass with `settings`.
[[nodiscard]] std::vector<glm::vec4> filtered(const lighting::CausticPassSettings& settings,
                                              const RectScene& scene, glm::ivec2 size,
                                              const std::vector<lighting::CausticPhoton>& photons);

/// relRMSE of an irradiance image's green channel against a uniform `expected` over the pixels
/// at least `margin` from the border, and their mean over `expected`.
[[nodiscard]] std::pair<double, double> uniform_error(const std::vector<glm::vec4>& image,
                                                      glm::ivec2 size, double expected, int margin);

/// `count` photons spread evenly (Fibonacci spiral) over a disc of `radius` around `centre`
/// on the plane spanned by unit axes a and b, with total power `power`.
[[nodiscard]] std::vector<lighting::CausticPhoton> disc_photons(const glm::vec3& centre,
                                                                const glm::vec3& a,
                                                                const glm::vec3& b, float radius,
                                                                int count, const glm::vec3& power);

}  // namespace luxel::test
