#include "luxel/world/vertex_wave.hpp"

#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "luxel/scene/components.hpp"
#include "luxel/world/mesh_shape.hpp"

namespace luxel::world {
namespace {

float number_or(const nlohmann::json& object, const char* key, float fallback) {
    const auto found = object.find(key);
    if (found == object.end() || !found->is_number()) {
        return fallback;
    }
    const auto value = found->get<double>();
    return std::isfinite(value) ? static_cast<float>(value) : fallback;
}

}  // namespace

std::optional<WaveParameters> read_wave(const nlohmann::json& luxel_extras) {
    if (!luxel_extras.is_object()) {
        return std::nullopt;
    }
    const auto found = luxel_extras.find("wave");
    if (found == luxel_extras.end() || !found->is_object()) {
        return std::nullopt;
    }
    WaveParameters wave;
    wave.amplitude = number_or(*found, "amplitude", wave.amplitude);
    wave.wavelength = number_or(*found, "wavelength", wave.wavelength);
    wave.speed = number_or(*found, "speed", wave.speed);
    if (const auto direction = found->find("direction");
        direction != found->end() && direction->is_array() && direction->size() == 2 &&
        (*direction)[0].is_number() && (*direction)[1].is_number()) {
        const glm::vec2 d((*direction)[0].get<float>(), (*direction)[1].get<float>());
        const float length = glm::length(d);
        if (length > 1e-6f && std::isfinite(length)) {
            wave.direction = d / length;
        }
    }
    if (!(wave.wavelength > 0.0f)) {
        wave.wavelength = WaveParameters{}.wavelength;
    }
    return wave;
}

scene::Mesh waved_mesh(const scene::Mesh& rest, const WaveParameters& wave, double time) {
    scene::Mesh out = rest;
    // k = 2 pi / L; the phase in double so that speed * time stays exact over long runs.
    const double k = 2.0 * std::numbers::pi / static_cast<double>(wave.wavelength);
    const double shift = static_cast<double>(wave.speed) * time;
    for (scene::Primitive& primitive : out.primitives) {
        const bool has_normals = primitive.normals.size() == primitive.positions.size();
        if (!has_normals) {
            primitive.normals.assign(primitive.positions.size(), glm::vec3(0.0f, 1.0f, 0.0f));
        }
        for (std::size_t i = 0; i < primitive.positions.size(); ++i) {
            glm::vec3& p = primitive.positions[i];
            glm::vec3& n = primitive.normals[i];
            const double along =
                static_cast<double>(wave.direction.x * p.x + wave.direction.y * p.z);
            const double phase = k * (along - shift);
            const auto height = static_cast<float>(wave.amplitude * std::sin(phase));
            const auto slope = static_cast<float>(wave.amplitude * k * std::cos(phase));
            // The gradient of h in the node's space, projected into the surface's tangent
            // plane: the normal tilts against it.
            const glm::vec3 gradient(slope * wave.direction.x, 0.0f, slope * wave.direction.y);
            const glm::vec3 unit = glm::length(n) > 1e-12f ? glm::normalize(n) : glm::vec3(0, 1, 0);
            const glm::vec3 tangential = gradient - unit * glm::dot(unit, gradient);
            p += unit * height;
            const glm::vec3 tilted = unit - tangential;
            // |unit - tangential| >= 1: tangential is orthogonal to the unit normal.
            n = tilted / glm::length(tilted);
        }
    }
    return out;
}

std::size_t update_waves(ecs::Registry& registry, double dt_seconds) {
    std::vector<std::pair<ecs::Entity, std::shared_ptr<const scene::Mesh>>> shaped;
    // A game that took the MeshInstance away is left alone.
    for (auto [entity, wave, instance] : registry.view<VertexWave, scene::MeshInstance>()) {
        (void)instance;
        if (wave.playing && std::isfinite(dt_seconds)) {
            wave.time += dt_seconds;
            // The shape repeats every wavelength / speed seconds.
            if (const double period = static_cast<double>(wave.wave.wavelength) /
                                      std::abs(static_cast<double>(wave.wave.speed));
                std::isfinite(period) && period > 0.0) {
                wave.time = std::fmod(wave.time, period);
                if (wave.time < 0.0) {
                    wave.time += period;
                }
            }
        }
        if (wave.shaped_at == wave.time) {
            continue;
        }
        const scene::Mesh& rest = wave.source->meshes.at(static_cast<std::size_t>(wave.mesh));
        shaped.emplace_back(
            entity, std::make_shared<const scene::Mesh>(waved_mesh(rest, wave.wave, wave.time)));
        wave.shaped_at = wave.time;
    }
    // Replaced after the view: a replace notifies observers, which must not run mid-iteration.
    for (auto& [entity, mesh] : shaped) {
        set_mesh_shape(registry, entity, std::move(mesh));
    }
    return shaped.size();
}

}  // namespace luxel::world
