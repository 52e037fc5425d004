#include "luxel/lighting/reference/reference_frame.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "luxel/runtime/error.hpp"

namespace luxel::lighting::reference {

ReferenceCamera ReferenceCamera::look_at(const glm::vec3& eye, const glm::vec3& target,
                                         float vertical_fov, int width, int height,
                                         const glm::vec3& up) {
    ReferenceCamera camera;
    camera.width = width;
    camera.height = height;
    glm::vec3 forward = target - eye;
    if (!(glm::length(forward) > 0.0f)) {
        throw Error("ReferenceCamera: the eye and the target coincide");
    }
    forward = glm::normalize(forward);
    // Looking straight along `up` leaves look_at without a plane: pick another up.
    const glm::vec3 safe_up =
        std::abs(glm::dot(forward, glm::normalize(up))) > 0.999f ? glm::vec3(0, 0, 1) : up;
    camera.view = glm::lookAt(eye, target, safe_up);
    const float aspect = height > 0 ? static_cast<float>(width) / static_cast<float>(height) : 1.0f;
    camera.projection = glm::perspective(vertical_fov, aspect, 0.01f, 1000.0f);
    return camera;
}

void ReferenceCamera::ray(double x, double y, glm::vec3& origin, glm::vec3& direction) const {
    const glm::mat4 inverse = glm::inverse(projection * view);
    const auto w = static_cast<double>(std::max(width, 1));
    const auto h = static_cast<double>(std::max(height, 1));
    const auto ndc_x = static_cast<float>(2.0 * x / w - 1.0);
    const auto ndc_y = static_cast<float>(1.0 - 2.0 * y / h);
    const glm::vec4 near_point = inverse * glm::vec4(ndc_x, ndc_y, -1.0f, 1.0f);
    const glm::vec4 mid_point = inverse * glm::vec4(ndc_x, ndc_y, 0.0f, 1.0f);
    const glm::vec3 a = glm::vec3(near_point) / near_point.w;
    const glm::vec3 b = glm::vec3(mid_point) / mid_point.w;
    origin = a;
    const glm::vec3 along = b - a;
    direction = glm::length(along) > 0.0f ? glm::normalize(along) : glm::vec3(0, 0, -1);
}

ReferenceFrame::ReferenceFrame(const ReferenceScene& scene, ReferenceCamera camera,
                               ReferenceFrameSettings settings)
    : scene_(&scene), camera_(camera), settings_(settings) {
    if (camera_.width <= 0 || camera_.height <= 0) {
        throw Error("ReferenceFrame: image size " + std::to_string(camera_.width) + "x" +
                    std::to_string(camera_.height) + " is empty");
    }
    const auto pixels =
        static_cast<std::size_t>(camera_.width) * static_cast<std::size_t>(camera_.height);
    sum_.assign(pixels, glm::dvec3(0.0));
    sum_squares_.assign(pixels, glm::dvec3(0.0));
}

void ReferenceFrame::run_pass(JobSystem& jobs, std::span<const glm::dvec3> caustic_irradiance) {
    const PathEstimator estimator(*scene_, settings_.paths, caustic_irradiance);
    const auto width = static_cast<std::size_t>(camera_.width);
    const std::uint64_t first = samples_;
    std::vector<PathCounters> rows(static_cast<std::size_t>(camera_.height));
    jobs.parallel_for(0, rows.size(), [&](std::size_t y) {
        for (std::size_t x = 0; x < width; ++x) {
            const std::size_t pixel = y * width + x;
            for (std::uint32_t s = 0; s < settings_.samples_per_pass; ++s) {
                // Pixel ids are offset past any texel id of the same seed's streams.
                SampleStream random(settings_.seed, (1ull << 40) + pixel, first + s);
                const glm::dvec2 jitter = random.next2();
                glm::vec3 origin;
                glm::vec3 direction;
                camera_.ray(static_cast<double>(x) + jitter.x, static_cast<double>(y) + jitter.y,
                            origin, direction);
                const glm::dvec3 radiance = estimator.radiance(origin, direction, random, rows[y]);
                sum_[pixel] += radiance;
                sum_squares_[pixel] += radiance * radiance;
            }
        }
    });
    for (const PathCounters& c : rows) {
        counters_.rays += c.rays;
        counters_.truncated += c.truncated;
        counters_.non_finite += c.non_finite;
    }
    samples_ += settings_.samples_per_pass;
    ++passes_;
}

Image ReferenceFrame::image() const {
    Image image(camera_.width, camera_.height, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    if (samples_ == 0) {
        return image;
    }
    const double n = static_cast<double>(samples_);
    for (int y = 0; y < camera_.height; ++y) {
        for (int x = 0; x < camera_.width; ++x) {
            const glm::dvec3 mean = sum_[static_cast<std::size_t>(y * camera_.width + x)] / n;
            image.set_pixel(x, y, glm::vec4(glm::vec3(mean), 1.0f));
        }
    }
    return image;
}

Image ReferenceFrame::standard_error_image() const {
    Image image(camera_.width, camera_.height, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    if (samples_ < 2) {
        return image;
    }
    const double n = static_cast<double>(samples_);
    for (int y = 0; y < camera_.height; ++y) {
        for (int x = 0; x < camera_.width; ++x) {
            const auto pixel = static_cast<std::size_t>(y * camera_.width + x);
            const glm::dvec3 mean = sum_[pixel] / n;
            const glm::dvec3 variance =
                glm::max(sum_squares_[pixel] / n - mean * mean, glm::dvec3(0.0)) * (n / (n - 1.0));
            image.set_pixel(x, y, glm::vec4(glm::vec3(glm::sqrt(variance / n)), 1.0f));
        }
    }
    return image;
}

double ReferenceFrame::relative_standard_error() const {
    if (samples_ < 2) {
        return 0.0;
    }
    const double n = static_cast<double>(samples_);
    double error = 0.0;
    double signal = 0.0;
    for (std::size_t pixel = 0; pixel < sum_.size(); ++pixel) {
        const glm::dvec3 mean = sum_[pixel] / n;
        const glm::dvec3 variance =
            glm::max(sum_squares_[pixel] / n - mean * mean, glm::dvec3(0.0)) * (n / (n - 1.0));
        error += (variance.x + variance.y + variance.z) / n;
        signal += glm::dot(mean, mean);
    }
    return signal > 0.0 ? std::sqrt(error / signal) : 0.0;
}

}  // namespace luxel::lighting::reference
