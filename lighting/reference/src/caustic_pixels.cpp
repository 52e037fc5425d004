#include "luxel/lighting/reference/caustic_pixels.hpp"

#include <cmath>

#include <glm/gtc/constants.hpp>

#include "luxel/lighting/core/photon_tracer.hpp"
#include "luxel/runtime/error.hpp"

namespace luxel::lighting::reference {

CausticPixels caustic_pixels(const ReferenceScene& scene, const ReferenceCamera& camera) {
    CausticPixels pixels;
    pixels.width = camera.width;
    pixels.height = camera.height;
    pixels.footprint_of_pixel.assign(
        static_cast<std::size_t>(camera.width) * static_cast<std::size_t>(camera.height), -1);
    const auto materials = scene.materials();
    for (int y = 0; y < camera.height; ++y) {
        for (int x = 0; x < camera.width; ++x) {
            glm::vec3 origin;
            glm::vec3 direction;
            camera.ray(x + 0.5, y + 0.5, origin, direction);
            const auto hit = scene.rays().intersect(origin, direction);
            if (!hit || hit->material >= materials.size()) {
                continue;
            }
            const TraceMaterial& material = materials[hit->material];
            const FacingNormals normals = facing_normals(*hit, direction);
            if (material.scattering != Scattering::Diffuse || !normals.front) {
                continue;
            }
            // The solid angle between the rays through the pixel's edge midpoints.
            glm::vec3 o;
            glm::vec3 left;
            glm::vec3 right;
            glm::vec3 top;
            glm::vec3 bottom;
            camera.ray(x, y + 0.5, o, left);
            camera.ray(x + 1.0, y + 0.5, o, right);
            camera.ray(x + 0.5, y, o, top);
            camera.ray(x + 0.5, y + 1.0, o, bottom);
            const double omega =
                glm::length(glm::cross(glm::dvec3(right - left), glm::dvec3(bottom - top)));
            if (!(omega > 0.0) || !std::isfinite(omega)) {
                throw Error(
                    "caustic_pixels: the camera's pixels subtend no solid angle "
                    "(orthographic?); a perspective camera is needed");
            }
            const double distance = glm::length(glm::dvec3(hit->position - origin));
            const double cos_theta = glm::dot(normals.geometric, -direction);
            const double area = camera_footprint_area(omega, distance, cos_theta);
            const auto pixel =
                static_cast<std::size_t>(y) * static_cast<std::size_t>(camera.width) +
                static_cast<std::size_t>(x);
            pixels.footprint_of_pixel[pixel] = static_cast<std::int64_t>(pixels.footprints.size());
            pixels.footprints.push_back(footprint_of_area(hit->position, normals.geometric, area));
            pixels.albedo.push_back(scene.diffuse_albedo(*hit, material));
        }
    }
    return pixels;
}

Image caustic_pixel_image(const CausticPixels& pixels, const CausticReference& caustics) {
    Image image(pixels.width, pixels.height, glm::vec4(0.0f));
    for (int y = 0; y < pixels.height; ++y) {
        for (int x = 0; x < pixels.width; ++x) {
            const std::int64_t f =
                pixels.footprint_of_pixel[static_cast<std::size_t>(y) *
                                              static_cast<std::size_t>(pixels.width) +
                                          static_cast<std::size_t>(x)];
            if (f < 0) {
                continue;
            }
            const auto i = static_cast<std::size_t>(f);
            const glm::dvec3 radiance =
                glm::dvec3(pixels.albedo[i]) / glm::pi<double>() * caustics.footprint_irradiance(i);
            image.set_pixel(x, y, glm::vec4(glm::vec3(radiance), 1.0f));
        }
    }
    return image;
}

double caustic_pixels_relative_standard_error(const CausticPixels& pixels,
                                              const CausticReference& caustics) {
    double error = 0.0;
    double signal = 0.0;
    for (std::size_t i = 0; i < pixels.footprints.size(); ++i) {
        const glm::dvec3 albedo(pixels.albedo[i]);
        const glm::dvec3 mean = albedo * caustics.footprint_irradiance(i);
        const glm::dvec3 se = albedo * caustics.footprint_standard_error(i);
        error += glm::dot(se, se);
        signal += glm::dot(mean, mean);
    }
    return signal > 0.0 ? std::sqrt(error / signal) : 0.0;
}

}  // namespace luxel::lighting::reference
