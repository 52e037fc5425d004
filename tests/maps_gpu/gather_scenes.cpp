#include "gather_scenes.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include <glm/gtc/constants.hpp>

#include "luxel/lighting/components.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/scene/gltf.hpp"
#include "test_paths.hpp"

namespace luxel::test {

std::unique_ptr<GlContext> make_gl_context() {
    GlContextOptions options;
    options.backend = GlBackend::Egl;
    options.width = 16;
    options.height = 16;
    return create_gl_context(options);
}

lighting::TriangleMesh box_mesh(const glm::vec3& lo, const glm::vec3& hi, bool inward,
                                std::int32_t first_surface) {
    lighting::TriangleMesh mesh;
    const glm::vec3 centre = 0.5f * (lo + hi);
    const glm::vec3 half = 0.5f * (hi - lo);
    for (int face = 0; face < 6; ++face) {
        const int axis = face / 2;
        const float side = face % 2 == 0 ? -1.0f : 1.0f;
        glm::vec3 outward(0.0f);
        outward[axis] = side;
        const glm::vec3 facing = inward ? -outward : outward;
        // u x v = facing, so the corners below wind counter-clockwise seen from `facing`.
        glm::vec3 u(0.0f);
        u[(axis + 1) % 3] = 1.0f;
        const glm::vec3 v = glm::cross(facing, u);
        const glm::vec3 c = centre + outward * half;
        const glm::vec3 su = u * half;
        const glm::vec3 sv = v * half;
        const auto base = static_cast<std::uint32_t>(mesh.positions.size());
        mesh.positions.insert(mesh.positions.end(),
                              {c - su - sv, c + su - sv, c + su + sv, c - su + sv});
        mesh.lightmap_uvs.insert(mesh.lightmap_uvs.end(), {{0, 0}, {1, 0}, {1, 1}, {0, 1}});
        mesh.indices.insert(mesh.indices.end(),
                            {base, base + 1, base + 2, base, base + 2, base + 3});
        mesh.surface_ids.insert(mesh.surface_ids.end(), 2, first_surface + face);
        mesh.material_ids.insert(mesh.material_ids.end(), 2, 0u);
    }
    return mesh;
}

lighting::RadianceAtlas constant_atlas(std::size_t surfaces, const glm::vec3& radiance,
                                       int page_size) {
    lighting::RadianceAtlas atlas;
    for (std::size_t s = 0; s < surfaces; ++s) {
        lighting::RadiancePage page(page_size);
        std::fill(page.texels.begin(), page.texels.end(), radiance);
        page.version = 1;
        atlas.pages.push_back(std::move(page));
        atlas.surface_page.push_back(static_cast<std::int32_t>(s));
    }
    return atlas;
}

glm::vec3 synthetic_radiance(int x, int y) {
    const auto fx = static_cast<float>(x);
    const auto fy = static_cast<float>(y);
    return {0.6f + 0.4f * std::sin(0.05f * fx), 0.5f + 0.3f * std::cos(0.04f * fy),
            0.4f + 0.2f * std::sin(0.03f * (fx + fy))};
}

std::filesystem::path level_path(const std::string& name) {
    return luxel::testing::source_dir() / "assets" / "levels" / (name + ".glb");
}

GatherLevel::GatherLevel(const std::string& name) {
    world::InstantiateOptions options;
    options.play_animations = false;
    instance = world::instantiate(
        registry, std::make_shared<scene::Scene>(scene::load_gltf(level_path(name))), options);
    transforms.update();
    world = std::make_unique<lighting::PhotonWorld>(registry);
    world->sync();

    // One atlas page per (scene, layout page): luxel-prep numbers pages per scene file.
    std::map<std::pair<const scene::Scene*, int>, std::int32_t> pages;
    for (const lighting::SurfaceInfo& info : world->surfaces()) {
        std::int32_t index = -1;
        const auto* layout = registry.try_get<lighting::LightmappedSurface>(info.entity);
        const auto* mesh = registry.try_get<scene::MeshInstance>(info.entity);
        if (layout != nullptr && mesh != nullptr && info.layout_id >= 0) {
            for (const scene::LightmapSurface& surface : layout->layout.surfaces) {
                if (surface.id != info.layout_id) {
                    continue;
                }
                const auto key = std::make_pair(mesh->source.get(), surface.page);
                auto found = pages.find(key);
                if (found == pages.end()) {
                    const int size = layout->layout.page_size;
                    lighting::RadiancePage page(size);
                    for (int y = 0; y < size; ++y) {
                        for (int x = 0; x < size; ++x) {
                            page.at(x, y) = synthetic_radiance(x, y);
                        }
                    }
                    page.mark_changed({0, 0, size, size});
                    found = pages.emplace(key, static_cast<std::int32_t>(atlas.pages.size())).first;
                    atlas.pages.push_back(std::move(page));
                }
                index = found->second;
            }
        }
        atlas.surface_page.push_back(index);
    }
}

std::vector<lighting::GatherTexel> GatherLevel::texels(std::size_t count, float lift) const {
    const lighting::RayScene& rays = scene();
    const glm::vec3 origin = 0.5f * (rays.bounds_min() + rays.bounds_max());
    std::vector<lighting::GatherTexel> found;
    // Fibonacci sphere: evenly spread directions, deterministic.
    const float golden = glm::pi<float>() * (3.0f - std::sqrt(5.0f));
    const std::size_t tries = 4 * count;
    for (std::size_t i = 0; i < tries; ++i) {
        const float z = 1.0f - 2.0f * (static_cast<float>(i) + 0.5f) / static_cast<float>(tries);
        const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        const float phi = golden * static_cast<float>(i);
        const glm::vec3 direction(r * std::cos(phi), z, r * std::sin(phi));
        const auto hit = rays.intersect(origin, direction);
        if (!hit || glm::dot(hit->geometric_normal, direction) >= 0.0f ||
            atlas.sample(hit->surface, hit->lightmap_uv) == glm::vec3(0.0f)) {
            continue;  // only front faces of light-mapped surfaces: texels a level would have
        }
        found.push_back({hit->position + lift * hit->geometric_normal, hit->geometric_normal});
    }
    // Every k-th hit, so the texels spread over the whole sphere of directions.
    if (found.size() <= count) {
        return found;
    }
    std::vector<lighting::GatherTexel> result;
    for (std::size_t i = 0; i < count; ++i) {
        result.push_back(found[i * found.size() / count]);
    }
    return result;
}

}  // namespace luxel::test
