#include "map_registry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <glm/gtc/constants.hpp>

#include "luxel/ecs/hierarchy.hpp"
#include "luxel/scene/image_decode.hpp"
#include "luxel/scene/texture_mean.hpp"
#include "map_support.hpp"

namespace luxel::lighting {
namespace {

glm::mat4 world_matrix(const ecs::Registry& registry, ecs::Entity entity) {
    if (const auto* world = registry.try_get<ecs::WorldTransform>(entity)) {
        return world->matrix;
    }
    return ecs::compute_world_matrix(registry, entity);
}

}  // namespace

using namespace map_support;
MapRegistry::MapRegistry(ecs::Registry& registry, const PhotonWorld& world)
    : registry_(registry),
      world_(world),
      moves_(registry.observe<ecs::WorldTransform>()),
      area_changes_(registry.observe<AreaLight>()),
      sky_changes_(registry.observe<SkyLight>(ecs::ObserverStart::WithExisting)) {}

bool MapRegistry::live(std::uint32_t s) const {
    const MapSurface& mapped = surfaces_.at(s);
    return !mapped.texels.texels.empty() && registry_.valid(mapped.entity);
}

std::int32_t MapRegistry::owner(std::int32_t page, int x, int y) const {
    const auto& owners = owners_.at(static_cast<std::size_t>(page));
    const auto size = static_cast<std::size_t>(aim_.pages[static_cast<std::size_t>(page)].size);
    return owners[static_cast<std::size_t>(y) * size + static_cast<std::size_t>(x)];
}

std::int32_t MapRegistry::page_index(const scene::Scene* source, int page, int page_size) {
    const auto key = std::make_pair(source, page);
    if (const auto found = pages_.find(key); found != pages_.end()) {
        return found->second;
    }
    const auto index = static_cast<std::int32_t>(aim_.pages.size());
    aim_.pages.emplace_back(page_size);
    iim_pages_.emplace_back(page_size);
    owners_.emplace_back(static_cast<std::size_t>(page_size) * static_cast<std::size_t>(page_size),
                         -1);
    pages_.emplace(key, index);
    return index;
}

void MapRegistry::add_surface(std::uint32_t surface) {
    const SurfaceInfo& info = world_.surfaces()[surface];
    MapSurface mapped;
    mapped.entity = info.entity;
    const auto* instance = registry_.try_get<scene::MeshInstance>(info.entity);
    const auto* layout = registry_.try_get<LightmappedSurface>(info.entity);
    std::int32_t page = -1;
    if (instance != nullptr && layout != nullptr && info.layout_id >= 0 && info.primitive >= 0) {
        const scene::Mesh& mesh = instance->geometry();
        const auto& primitive = mesh.primitives.at(static_cast<std::size_t>(info.primitive));
        for (const auto& entry : layout->layout.surfaces) {
            if (entry.id != info.layout_id) {
                continue;
            }
            page = page_index(instance->source.get(), entry.page, layout->layout.page_size);
            mapped.texels = rasterize_surface(primitive, entry.page, layout->layout.page_size);
            mapped.footprint = SurfaceFootprint(primitive, mapped.texels);
            break;
        }
        if (primitive.material >= 0) {
            const scene::Material& material =
                instance->source->materials.at(static_cast<std::size_t>(primitive.material));
            // The albedo the photon tracer bounces with (textured: factor x the texture's
            // mean), so the AIM and the photons agree.
            mapped.albedo = scene::mean_diffuse_albedo(*instance->source, material);
            mapped.content =
                material.base_color_image >= 0 ? IimContent::Irradiance : IimContent::Radiance;
        }
    }
    if (instance != nullptr && info.primitive >= 0) {
        const auto& primitive =
            instance->geometry().primitives.at(static_cast<std::size_t>(info.primitive));
        if (primitive.material >= 0) {
            const scene::Material& material =
                instance->source->materials.at(static_cast<std::size_t>(primitive.material));
            if (material.is_emissive()) {
                // The gathers see a surface's mean emission (the photons emit each piece's own:
                // EmissionPieces), so an emissive texture's bright patch lights the room with
                // the texture's power, not the factor's.
                const scene::LinearImage texels =
                    primitive.texcoords0.size() == primitive.positions.size()
                        ? scene::emissive_texels(*instance->source, material)
                        : scene::LinearImage{};
                mapped.material_emission = sanitized(scene::mean_emission(
                    primitive, scene::triangle_emission(primitive, material, texels)));
            }
        }
    }
    aim_.surface_page.push_back(page);
    aim_.surface_emission.push_back(glm::vec3(0.0f));
    if (page >= 0) {
        auto& owners = owners_[static_cast<std::size_t>(page)];
        const auto size = static_cast<std::size_t>(mapped.texels.page_size);
        for (const SurfaceTexel& texel : mapped.texels.texels) {
            owners[static_cast<std::size_t>(texel.y) * size + static_cast<std::size_t>(texel.x)] =
                static_cast<std::int32_t>(surface);
        }
    }
    AxisBox local;
    for (const SurfaceTexel& texel : mapped.texels.texels) {
        local.add(texel.position);
    }
    local_boxes_.push_back(local);
    surface_boxes_.emplace_back();
    if (!mapped.texels.texels.empty()) {
        mapped_surfaces_.push_back(surface);
    }
    surfaces_.push_back(std::move(mapped));
    surfaces_of_[info.entity].push_back(surface);
    refresh_transform(surface);
    if (refresh_emission(surface)) {
        ++emission_version_;
    }
}

bool MapRegistry::refresh_emission(std::uint32_t surface) {
    const MapSurface& mapped = surfaces_[surface];
    glm::vec3 emission(0.0f);
    // Emission counts where the photon world emits photons for it: an entity with an enabled
    // AreaLight (scene instantiation gives every emissive mesh one).
    const auto* area =
        registry_.valid(mapped.entity) ? registry_.try_get<AreaLight>(mapped.entity) : nullptr;
    if (area != nullptr && area->enabled) {
        emission = sanitized(mapped.material_emission * area->scale);
    }
    glm::vec3& current = aim_.surface_emission[surface];
    if (current == emission) {
        return false;
    }
    current = emission;
    return true;
}

void MapRegistry::refresh_transform(std::uint32_t surface) {
    MapSurface& mapped = surfaces_[surface];
    if (!registry_.valid(mapped.entity)) {
        return;
    }
    mapped.to_world = world_matrix(registry_, mapped.entity);
    // Light maps assume a similarity transform (no shear): its scale is the cube root of the
    // volume change.
    const double scale =
        std::cbrt(std::abs(static_cast<double>(glm::determinant(glm::mat3(mapped.to_world)))));
    mapped.world_metres_per_texel = mapped.texels.metres_per_texel * scale;
    surface_boxes_[surface] = transformed(local_boxes_[surface], mapped.to_world);
}

std::vector<std::uint32_t> MapRegistry::texels_inside(std::uint32_t surface,
                                                      const GeometryChange& region) const {
    // Tested in the surface's own space, where its texels are kept: the region's box moved
    // there (a little larger where the surface is rotated) instead of every texel moved out.
    const MapSurface& mapped = surfaces_[surface];
    const AxisBox local = transformed(region, glm::inverse(mapped.to_world));
    const std::vector<SurfaceTexel>& texels = mapped.texels.texels;
    std::vector<std::uint32_t> inside;
    for (std::size_t i = 0; i < texels.size(); ++i) {
        if (local.contains(texels[i].position)) {
            inside.push_back(static_cast<std::uint32_t>(i));
        }
    }
    return inside;
}

void MapRegistry::find_nearby_changes() {
    nearby_changes_.clear();
    for (const GeometryChange& change : world_.geometry_changes()) {
        if (change.empty() || !finite_vector(change.min) || !finite_vector(change.max)) {
            continue;
        }
        const glm::vec3 margin = glm::vec3(0.5f * glm::length(change.max - change.min));
        const GeometryChange region{change.min - margin, change.max + margin};
        // Every change against every surface would be quadratic on a level of many meshes
        // (300,000 nodes, none light-mapped, took minutes): only surfaces with texels count.
        for (const std::uint32_t s : mapped_surfaces_) {
            if (surface_boxes_[s].meets(region) && live(s)) {
                nearby_changes_.push_back({s, region, change, texels_inside(s, region)});
            }
        }
    }
}

bool MapRegistry::refresh_skies() {
    std::vector<RadianceAtlas::Sky> skies;
    for (auto [entity, sky] : registry_.view<SkyLight>()) {
        if (sky.enabled && sky.radiance != nullptr && !sky.radiance->black() &&
            sky.effective_scale() > 0.0f) {
            skies.push_back({sky.radiance, sky.effective_scale()});
        }
    }
    const bool same = std::equal(skies.begin(), skies.end(), aim_.skies.begin(), aim_.skies.end(),
                                 [](const RadianceAtlas::Sky& a, const RadianceAtlas::Sky& b) {
                                     return a.radiance == b.radiance && a.scale == b.scale;
                                 });
    if (same) {
        return false;
    }
    aim_.skies = std::move(skies);
    return true;
}

void MapRegistry::find_object_seams(std::span<const std::uint32_t> added) {
    std::map<ecs::Entity, std::vector<SeamSurface>> objects;
    for (const std::uint32_t s : added) {
        const SurfaceInfo& info = world_.surfaces()[s];
        const MapSurface& mapped = surfaces_[s];
        const auto* instance = registry_.try_get<scene::MeshInstance>(info.entity);
        if (instance == nullptr || info.primitive < 0 || page_of(s) < 0) {
            continue;
        }
        const auto& primitives = instance->geometry().primitives;
        if (static_cast<std::size_t>(info.primitive) >= primitives.size()) {
            continue;
        }
        objects[info.entity].push_back({s, &primitives[static_cast<std::size_t>(info.primitive)],
                                        page_of(s), mapped.texels.page_size, mapped.content,
                                        mapped.albedo});
    }
    for (const auto& [entity, object] : objects) {
        std::vector<SeamSample> samples = find_seams(object);
        if (!samples.empty()) {
            seams_.push_back(std::move(samples));
        }
    }
}

void MapRegistry::sync() {
    std::vector<std::uint32_t> added;
    for (auto s = static_cast<std::uint32_t>(surfaces_.size()); s < world_.surfaces().size(); ++s) {
        add_surface(s);
        added.push_back(s);
    }
    if (!added.empty()) {
        find_object_seams(added);
    }
    area_changes_.consume([&](ecs::Entity entity, ecs::ChangeKind) {
        const auto found = surfaces_of_.find(entity);
        if (found == surfaces_of_.end()) {
            return;
        }
        for (std::uint32_t surface : found->second) {
            if (refresh_emission(surface)) {
                ++emission_version_;
            }
        }
    });
    bool sky_touched = false;
    sky_changes_.consume([&](ecs::Entity, ecs::ChangeKind) { sky_touched = true; });
    // A sky's direct light on every surface comes from the gathers, as an area light's does:
    // a changed sky re-gathers them all.
    if (sky_touched && refresh_skies()) {
        ++emission_version_;
    }
    std::fill(moved_.begin(), moved_.end(), 0);
    moved_.resize(surfaces_.size(), 0);
    moves_.consume([&](ecs::Entity entity, ecs::ChangeKind kind) {
        if (kind == ecs::ChangeKind::Destroyed) {
            return;
        }
        const auto found = surfaces_of_.find(entity);
        if (found == surfaces_of_.end()) {
            return;
        }
        for (std::uint32_t surface : found->second) {
            refresh_transform(surface);
            moved_[surface] = 1;
        }
    });
    find_nearby_changes();
}

namespace {

GatherTexel to_world(const MapSurface& mapped, const glm::mat3& normal_matrix,
                     const SurfaceTexel& texel) {
    GatherTexel world;
    world.position = glm::vec3(mapped.to_world * glm::vec4(texel.position, 1.0f));
    const glm::vec3 n = normal_matrix * texel.normal;
    const float length = glm::length(n);
    world.normal = length > 0.0f && std::isfinite(length) ? n / length : texel.normal;
    return world;
}

}  // namespace

std::vector<GatherTexel> MapRegistry::world_texels(std::uint32_t surface) const {
    const MapSurface& mapped = surfaces_.at(surface);
    const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(mapped.to_world)));
    std::vector<GatherTexel> texels;
    texels.reserve(mapped.texels.texels.size());
    for (const SurfaceTexel& texel : mapped.texels.texels) {
        texels.push_back(to_world(mapped, normal_matrix, texel));
    }
    return texels;
}

std::vector<GatherTexel> MapRegistry::world_texels(std::uint32_t surface,
                                                   std::span<const std::uint32_t> indices) const {
    const MapSurface& mapped = surfaces_.at(surface);
    const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(mapped.to_world)));
    std::vector<GatherTexel> texels;
    texels.reserve(indices.size());
    for (const std::uint32_t i : indices) {
        texels.push_back(to_world(mapped, normal_matrix, mapped.texels.texels.at(i)));
    }
    return texels;
}

}  // namespace luxel::lighting
