#pragma once

// Field-by-field comparison of two scenes with a float tolerance (the writer normalises
// quaternions and normals, which may move the last bit).

#include <cmath>

#include <gtest/gtest.h>

#include "luxel/scene/scene.hpp"

namespace luxel::testing {

inline constexpr float kRoundTripTolerance = 1e-5f;

template <typename Vec>
void expect_near_vectors(const std::vector<Vec>& a, const std::vector<Vec>& b,
                         const std::string& what) {
    ASSERT_EQ(a.size(), b.size()) << what;
    for (std::size_t i = 0; i < a.size(); ++i) {
        for (int c = 0; c < Vec::length(); ++c) {
            ASSERT_NEAR(a[i][c], b[i][c], kRoundTripTolerance) << what << " element " << i;
        }
    }
}

inline void expect_near(const glm::vec3& a, const glm::vec3& b, const std::string& what) {
    expect_near_vectors(std::vector<glm::vec3>{a}, std::vector<glm::vec3>{b}, what);
}

inline void expect_same_scene(const scene::Scene& a, const scene::Scene& b) {
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.sky, b.sky);
    EXPECT_EQ(a.roots, b.roots);

    ASSERT_EQ(a.nodes.size(), b.nodes.size());
    for (std::size_t i = 0; i < a.nodes.size(); ++i) {
        const scene::Node& x = a.nodes[i];
        const scene::Node& y = b.nodes[i];
        const std::string what = "node " + std::to_string(i) + " " + x.name;
        EXPECT_EQ(x.name, y.name) << what;
        EXPECT_EQ(x.parent, y.parent) << what;
        EXPECT_EQ(x.children, y.children) << what;
        EXPECT_EQ(x.mesh, y.mesh) << what;
        EXPECT_EQ(x.light, y.light) << what;
        EXPECT_EQ(x.camera, y.camera) << what;
        expect_near(x.translation, y.translation, what + " translation");
        expect_near(x.scale, y.scale, what + " scale");
        // q and -q are the same rotation.
        EXPECT_NEAR(std::abs(glm::dot(x.rotation, y.rotation)), 1.0f, kRoundTripTolerance) << what;
        EXPECT_EQ(x.flags.dynamic, y.flags.dynamic) << what;
        EXPECT_EQ(x.flags.light_enabled, y.flags.light_enabled) << what;
        EXPECT_EQ(x.flags.light_radius, y.flags.light_radius) << what;
        EXPECT_EQ(x.flags.raw, y.flags.raw) << what;
    }

    ASSERT_EQ(a.meshes.size(), b.meshes.size());
    for (std::size_t m = 0; m < a.meshes.size(); ++m) {
        EXPECT_EQ(a.meshes[m].name, b.meshes[m].name);
        ASSERT_EQ(a.meshes[m].primitives.size(), b.meshes[m].primitives.size());
        for (std::size_t p = 0; p < a.meshes[m].primitives.size(); ++p) {
            const scene::Primitive& x = a.meshes[m].primitives[p];
            const scene::Primitive& y = b.meshes[m].primitives[p];
            const std::string what =
                "mesh " + std::to_string(m) + " primitive " + std::to_string(p);
            expect_near_vectors(x.positions, y.positions, what + " positions");
            expect_near_vectors(x.normals, y.normals, what + " normals");
            expect_near_vectors(x.texcoords0, y.texcoords0, what + " texcoords0");
            expect_near_vectors(x.texcoords1, y.texcoords1, what + " texcoords1");
            EXPECT_EQ(x.indices, y.indices) << what;
            EXPECT_EQ(x.material, y.material) << what;
        }
    }

    ASSERT_EQ(a.materials.size(), b.materials.size());
    for (std::size_t i = 0; i < a.materials.size(); ++i) {
        const scene::Material& x = a.materials[i];
        const scene::Material& y = b.materials[i];
        const std::string what = "material " + x.name;
        EXPECT_EQ(x.name, y.name);
        for (int c = 0; c < 4; ++c) {
            EXPECT_NEAR(x.base_color[c], y.base_color[c], kRoundTripTolerance) << what;
        }
        EXPECT_EQ(x.base_color_image, y.base_color_image) << what;
        EXPECT_EQ(x.emissive_image, y.emissive_image) << what;
        EXPECT_NEAR(x.metallic, y.metallic, kRoundTripTolerance) << what;
        EXPECT_NEAR(x.roughness, y.roughness, kRoundTripTolerance) << what;
        expect_near(x.emitted_radiance(), y.emitted_radiance(), what + " emission");
        EXPECT_NEAR(x.transmission, y.transmission, kRoundTripTolerance) << what;
        EXPECT_NEAR(x.ior, y.ior, kRoundTripTolerance) << what;
        EXPECT_NEAR(x.thickness, y.thickness, kRoundTripTolerance) << what;
        // Infinite (no absorption) stays infinite; a finite distance within the tolerance.
        EXPECT_EQ(std::isinf(x.attenuation_distance), std::isinf(y.attenuation_distance)) << what;
        if (!std::isinf(x.attenuation_distance)) {
            EXPECT_NEAR(x.attenuation_distance, y.attenuation_distance, kRoundTripTolerance)
                << what;
        }
        expect_near(x.attenuation_color, y.attenuation_color, what + " attenuation colour");
        EXPECT_EQ(x.double_sided, y.double_sided) << what;
        EXPECT_EQ(x.is_specular(), y.is_specular()) << what;
        EXPECT_EQ(x.is_emissive(), y.is_emissive()) << what;
    }

    ASSERT_EQ(a.images.size(), b.images.size());
    for (std::size_t i = 0; i < a.images.size(); ++i) {
        EXPECT_EQ(a.images[i].name, b.images[i].name);
        EXPECT_EQ(a.images[i].mime_type, b.images[i].mime_type);
        EXPECT_EQ(a.images[i].encoded, b.images[i].encoded);
    }

    ASSERT_EQ(a.lights.size(), b.lights.size());
    for (std::size_t i = 0; i < a.lights.size(); ++i) {
        const scene::Light& x = a.lights[i];
        const scene::Light& y = b.lights[i];
        EXPECT_EQ(x.name, y.name);
        EXPECT_EQ(x.type, y.type) << x.name;
        expect_near(x.color * x.intensity, y.color * y.intensity, x.name + " colour*intensity");
        expect_near(x.radiant_power(), y.radiant_power(), x.name + " power");
        EXPECT_NEAR(x.range, y.range, kRoundTripTolerance) << x.name;
        if (x.type == scene::LightType::Spot) {
            EXPECT_NEAR(x.inner_cone_angle, y.inner_cone_angle, kRoundTripTolerance);
            EXPECT_NEAR(x.outer_cone_angle, y.outer_cone_angle, kRoundTripTolerance);
        }
    }

    ASSERT_EQ(a.cameras.size(), b.cameras.size());
    for (std::size_t i = 0; i < a.cameras.size(); ++i) {
        const scene::Camera& x = a.cameras[i];
        const scene::Camera& y = b.cameras[i];
        EXPECT_EQ(x.name, y.name);
        EXPECT_EQ(x.perspective, y.perspective) << x.name;
        EXPECT_EQ(x.zfar, y.zfar) << x.name;
        EXPECT_FLOAT_EQ(x.znear, y.znear) << x.name;
        if (x.perspective) {
            EXPECT_FLOAT_EQ(x.yfov, y.yfov) << x.name;
            EXPECT_EQ(x.aspect_ratio, y.aspect_ratio) << x.name;
        } else {
            EXPECT_FLOAT_EQ(x.xmag, y.xmag) << x.name;
            EXPECT_FLOAT_EQ(x.ymag, y.ymag) << x.name;
        }
    }

    ASSERT_EQ(a.animations.size(), b.animations.size());
    for (std::size_t i = 0; i < a.animations.size(); ++i) {
        const scene::Animation& x = a.animations[i];
        const scene::Animation& y = b.animations[i];
        EXPECT_EQ(x.name, y.name);
        ASSERT_EQ(x.channels.size(), y.channels.size()) << x.name;
        for (std::size_t c = 0; c < x.channels.size(); ++c) {
            EXPECT_EQ(x.channels[c].node, y.channels[c].node) << x.name;
            EXPECT_EQ(x.channels[c].property, y.channels[c].property) << x.name;
            EXPECT_EQ(x.channels[c].sampler, y.channels[c].sampler) << x.name;
        }
        ASSERT_EQ(x.samplers.size(), y.samplers.size()) << x.name;
        for (std::size_t s = 0; s < x.samplers.size(); ++s) {
            EXPECT_EQ(x.samplers[s].interpolation, y.samplers[s].interpolation) << x.name;
            EXPECT_EQ(x.samplers[s].times, y.samplers[s].times) << x.name;
            expect_near_vectors(x.samplers[s].values, y.samplers[s].values,
                                x.name + " sampler " + std::to_string(s));
        }
        EXPECT_FLOAT_EQ(x.duration(), y.duration());
    }
}

}  // namespace luxel::testing
