#include "caustic_test_support.hpp"

#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

namespace luxel::test {

std::unique_ptr<GlContext> make_caustic_gl_context() {
    GlContextOptions options;
    options.backend = GlBackend::Egl;
    options.width = 16;
    options.height = 16;
    return create_gl_context(options);
}

lighting::CausticCamera look_at(const glm::vec3& eye, const glm::vec3& target, glm::ivec2 viewport,
                                float vertical_fov) {
    const glm::vec3 forward = glm::normalize(target - eye);
    const glm::vec3 up = std::abs(forward.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    return lighting::CausticCamera::perspective(glm::lookAt(eye, target, up), vertical_fov,
                                                viewport, 0.1f, 100.0f);
}

RectScene::RectScene(const lighting::CausticCamera& camera, std::vector<Rect> rects)
    : camera_(camera), rects_(std::move(rects)) {
    const glm::ivec2 size = camera.viewport;
    std::vector<float> depth(static_cast<std::size_t>(size.x) * static_cast<std::size_t>(size.y),
                             1.0f);
    const glm::mat4 view_projection = camera.projection * camera.view;
    for (int y = 0; y < size.y; ++y) {
        for (int x = 0; x < size.x; ++x) {
            if (const auto p = hit(x, y)) {
                const glm::vec4 clip = view_projection * glm::vec4(*p, 1.0f);
                depth[static_cast<std::size_t>(y * size.x + x)] = 0.5f * clip.z / clip.w + 0.5f;
            }
        }
    }
    depth_ = gl::Texture::create_2d(GL_DEPTH_COMPONENT32F, size.x, size.y);
    glTextureParameteri(depth_.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(depth_.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(depth_.id(), GL_TEXTURE_COMPARE_MODE, GL_NONE);
    glTextureSubImage2D(depth_.id(), 0, 0, 0, size.x, size.y, GL_DEPTH_COMPONENT, GL_FLOAT,
                        depth.data());
}

std::optional<std::pair<glm::vec3, int>> RectScene::cast(const glm::vec2& window) const {
    const glm::mat4 inverse = glm::inverse(camera_.projection * camera_.view);
    const glm::vec2 ndc = window / glm::vec2(camera_.viewport) * 2.0f - 1.0f;
    const glm::vec4 near = inverse * glm::vec4(ndc, -1.0f, 1.0f);
    const glm::vec4 far = inverse * glm::vec4(ndc, 1.0f, 1.0f);
    const glm::dvec3 origin = glm::dvec3(near) / static_cast<double>(near.w);
    const glm::dvec3 direction =
        glm::normalize(glm::dvec3(far) / static_cast<double>(far.w) - origin);
    double best = std::numeric_limits<double>::infinity();
    int best_rect = -1;
    for (std::size_t r = 0; r < rects_.size(); ++r) {
        const glm::dvec3 c(rects_[r].centre);
        const glm::dvec3 u(rects_[r].u);
        const glm::dvec3 v(rects_[r].v);
        const glm::dvec3 n = glm::cross(u, v);
        const double denom = glm::dot(n, direction);
        if (std::abs(denom) < 1e-12) {
            continue;
        }
        const double t = glm::dot(n, c - origin) / denom;
        const glm::dvec3 p = origin + t * direction - c;
        const double s = glm::dot(p, u) / glm::dot(u, u);
        const double q = glm::dot(p, v) / glm::dot(v, v);
        if (t > 0.0 && t < best && std::abs(s) <= 1.0 && std::abs(q) <= 1.0) {
            best = t;
            best_rect = static_cast<int>(r);
        }
    }
    if (best_rect < 0) {
        return std::nullopt;
    }
    return std::make_pair(glm::vec3(origin + best * direction), best_rect);
}

std::optional<glm::vec3> RectScene::hit_window(const glm::vec2& window) const {
    const auto h = cast(window);
    return h ? std::optional<glm::vec3>(h->first) : std::nullopt;
}

std::optional<glm::vec3> RectScene::hit(int x, int y) const {
    return hit_window(glm::vec2(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f));
}

double RectScene::view_depth(int x, int y) const {
    const auto p = hit(x, y);
    return p ? -static_cast<double>((camera_.view * glm::vec4(*p, 1.0f)).z) : 0.0;
}

double RectScene::pixel_area(int x, int y) const {
    const auto h = cast(glm::vec2(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f));
    if (!h) {
        return 0.0;
    }
    const Rect& rect = rects_[static_cast<std::size_t>(h->second)];
    const glm::dvec3 n_world = glm::normalize(glm::cross(glm::dvec3(rect.u), glm::dvec3(rect.v)));
    const glm::dvec3 n = glm::dmat3(glm::dmat4(camera_.view)) * n_world;
    const glm::dvec3 view = glm::dvec3(camera_.view * glm::vec4(h->first, 1.0f));
    const double z = -view.z;
    return lighting::caustic_pixel_area(camera_, z) / std::abs(glm::dot(n, view / z));
}

std::vector<glm::vec4> read_rgba(GLuint texture, glm::ivec2 size) {
    std::vector<glm::vec4> pixels(static_cast<std::size_t>(size.x) *
                                  static_cast<std::size_t>(size.y));
    glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT,
                      static_cast<GLsizei>(pixels.size() * sizeof(glm::vec4)), pixels.data());
    return pixels;
}

glm::dvec3 total_power(const std::vector<glm::vec4>& image, const RectScene& scene) {
    glm::dvec3 sum(0.0);
    const glm::ivec2 size = scene.camera().viewport;
    for (int y = 0; y < size.y; ++y) {
        for (int x = 0; x < size.x; ++x) {
            const glm::vec4& e = image[static_cast<std::size_t>(y * size.x + x)];
            if (e.r != 0.0f || e.g != 0.0f || e.b != 0.0f) {
                sum += glm::dvec3(e) * scene.pixel_area(x, y);
            }
        }
    }
    return sum;
}

std::vector<lighting::CausticPhoton> disc_photons(const glm::vec3& centre, const glm::vec3& a,
                                                  const glm::vec3& b, float radius, int count,
                                                  const glm::vec3& power) {
    std::vector<lighting::CausticPhoton> photons;
    const double golden = 3.14159265358979323846 * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < count; ++i) {
        const double r = static_cast<double>(radius) * std::sqrt((i + 0.5) / count);
        const double phi = golden * i;
        lighting::CausticPhoton photon;
        photon.position = centre + static_cast<float>(r * std::cos(phi)) * a +
                          static_cast<float>(r * std::sin(phi)) * b;
        photon.power = power / static_cast<float>(count);
        photons.push_back(photon);
    }
    return photons;
}

std::vector<glm::vec4> filtered(const lighting::CausticPassSettings& settings,
                                const RectScene& scene, glm::ivec2 size,
                                const std::vector<lighting::CausticPhoton>& photons) {
    lighting::CausticPass pass(settings, size);
    pass.upload(photons);
    pass.render(scene.camera(), scene.depth_texture().id());
    return read_rgba(pass.irradiance_texture(), size);
}

std::pair<double, double> uniform_error(const std::vector<glm::vec4>& image, glm::ivec2 size,
                                        double expected, int margin) {
    double squares = 0.0;
    double sum = 0.0;
    double n = 0.0;
    for (int y = margin; y < size.y - margin; ++y) {
        for (int x = margin; x < size.x - margin; ++x) {
            const double e = image[static_cast<std::size_t>(y * size.x + x)].g;
            squares += (e - expected) * (e - expected);
            sum += e;
            n += 1.0;
        }
    }
    return {std::sqrt(squares / n) / expected, sum / n / expected};
}

}  // namespace luxel::test
