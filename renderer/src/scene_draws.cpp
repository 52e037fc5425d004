#include "scene_draws.hpp"

#include <cmath>
#include <map>
#include <utility>

#include "frame_lights.hpp"
#include "luxel/lighting/core/lighting_system.hpp"
#include "luxel/scene/volume.hpp"

namespace luxel::renderer {
namespace {

/// Fresnel reflectance at normal incidence of a dielectric of index `ior` in air.
float dielectric_f0(float ior) {
    const float r = (ior - 1.0f) / (ior + 1.0f);
    return r * r;
}

DrawMaterial material_of(const scene::Scene& source, int index, float emission_scale,
                         bool specular_pass) {
    const scene::Material fallback;
    const scene::Material& m =
        index >= 0 && static_cast<std::size_t>(index) < source.materials.size()
            ? source.materials[static_cast<std::size_t>(index)]
            : fallback;
    DrawMaterial out;
    const glm::vec3 base = glm::clamp(glm::vec3(m.base_color), 0.0f, 1.0f);
    out.emission = m.emitted_radiance() * emission_scale;
    out.double_sided = m.double_sided;
    out.ior = m.ior;
    if (m.is_specular() && specular_pass) {
        const glm::vec3 f0 =
            m.transmission > 0.0f ? glm::vec3(dielectric_f0(m.ior)) : base;  // glass : mirror
        out.specular = glm::vec4(glm::max(f0, glm::vec3(1e-3f)), m.transmission);
        // Glass is tinted by its base colour on the way through; kept in albedo's place.
        out.albedo = glm::vec3(0.0f);
    } else {
        out.albedo = base;
    }
    return out;
}

/// What a view ray through glass keeps besides Fresnel, as the photons and the reference
/// count it: the base colour once per surface crossed (in and out of a closed solid, once
/// through an open sheet) and, in a closed solid, the inside's absorption over the volume's
/// thickness (an open sheet has no inside: the photons never meet its back face from within).
/// The thickness is KHR_materials_volume's rasteriser model, the mesh's units times the
/// object's scale: one length for every pixel (a sphere's rim as thick as its centre), where
/// the photons and the reference measure each path.
glm::vec4 glass_transmittance(const scene::Material& m, bool closed, const glm::mat4& model) {
    const glm::vec3 tint = glm::clamp(glm::vec3(m.base_color), 0.0f, 1.0f);
    if (!closed) {
        return {tint, 1.0f};
    }
    const float scale = std::cbrt(std::abs(glm::determinant(glm::mat3(model))));
    return {tint * tint * scene::volume_transmittance(m, m.thickness * scale), 2.0f};
}

}  // namespace

void build_draw_list(ecs::Registry& registry, const lighting::LightingSystem& lighting,
                     MeshCache& meshes, std::uint64_t frame, bool specular_pass, bool skin_on_gpu,
                     DrawList& out) {
    out.items.clear();
    out.primitives.clear();
    out.bounds = Bounds{};
    out.joints.clear();

    // (entity, primitive) -> surface id, for the light-map lookups.
    std::map<std::pair<ecs::Entity, int>, std::size_t> surface_of;
    const auto& surfaces = lighting.photons().surfaces();
    for (std::size_t s = 0; s < surfaces.size(); ++s) {
        surface_of.emplace(std::make_pair(surfaces[s].entity, surfaces[s].primitive), s);
    }
    const lighting::IlluminationMaps& maps = lighting.maps();
    const auto& surface_page = maps.aim().surface_page;
    const auto map_surfaces = maps.surfaces();

    for (auto [entity, instance] : registry.view<scene::MeshInstance>()) {
        if (!instance.source || instance.mesh < 0 ||
            static_cast<std::size_t>(instance.mesh) >= instance.source->meshes.size()) {
            continue;
        }
        DrawItem item;
        item.entity = entity;
        item.mesh = &meshes.get(instance, frame, skin_on_gpu);
        item.model = entity_world_matrix(registry, entity);
        item.normal_matrix = glm::transpose(glm::inverse(glm::mat3(item.model)));
        item.mirrored = glm::determinant(glm::mat3(item.model)) < 0.0f;
        const bool skinned = item.mesh->skinned && instance.joint_matrices && instance.posed;
        if (skinned) {
            item.first_joint = out.joints.add(*instance.joint_matrices);
            item.joint_count = static_cast<std::int32_t>(instance.joint_matrices->size());
        }
        item.bounds = meshes.bounds(instance, frame).transformed(item.model);
        item.first = out.primitives.size();
        float emission_scale = 1.0f;
        if (const auto* area = registry.try_get<lighting::AreaLight>(entity)) {
            emission_scale = area->enabled ? area->scale : 0.0f;
        }
        for (std::size_t p = 0; p < item.mesh->primitives.size(); ++p) {
            DrawPrimitive draw;
            draw.range = &item.mesh->primitives[p];
            draw.material =
                material_of(*instance.source, draw.range->material, emission_scale, specular_pass);
            if (draw.material.specular.a > 0.0f) {
                const scene::Material& glass =
                    instance.source->materials.at(static_cast<std::size_t>(draw.range->material));
                draw.material.transmittance =
                    glass_transmittance(glass, draw.range->closed, item.model);
                draw.material.tint = glm::clamp(glm::vec3(glass.base_color), 0.0f, 1.0f);
                if (scene::absorbs_inside(glass)) {
                    // Metres of path, as the photons measure it (TraceMaterial).
                    draw.material.attenuation =
                        glm::vec4(glass.attenuation_color, glass.attenuation_distance);
                }
            }
            // Specular materials draw no diffuse albedo (it is zero), so they need no texture.
            draw.material.base_color_texture =
                draw.range->base_color && draw.material.albedo != glm::vec3(0.0f)
                    ? draw.range->base_color->id()
                    : meshes.white_texture();
            draw.material.emissive_texture =
                draw.range->emissive && draw.material.emission != glm::vec3(0.0f)
                    ? draw.range->emissive->id()
                    : meshes.white_texture();
            item.specular = item.specular || draw.material.specular.r > 0.0f;
            const auto found = surface_of.find(std::make_pair(entity, static_cast<int>(p)));
            if (found != surface_of.end() && found->second < surface_page.size() &&
                found->second < map_surfaces.size() && draw.material.specular.r <= 0.0f) {
                const std::int32_t page = surface_page[found->second];
                if (page >= 0) {
                    draw.material.lightmap =
                        glm::vec2(static_cast<float>(page), map_surfaces[found->second].content ==
                                                                    lighting::IimContent::Irradiance
                                                                ? 1.0f
                                                                : 0.0f);
                }
            }
            out.primitives.push_back(draw);
        }
        item.count = out.primitives.size() - item.first;
        out.bounds.add(item.bounds);
        out.items.push_back(item);
    }
    // The buffer is known only once every skinned item has added its matrices (it may grow).
    out.joints.upload();
    for (DrawItem& item : out.items) {
        if (item.first_joint >= 0) {
            item.joint_buffer = out.joints.buffer();
        }
    }
}

void bind_draw_item(const gl::Program& program, const DrawItem& item) {
    program.set("u_model", item.model);
    program.set("u_normal_matrix", item.normal_matrix);
    program.set("u_first_joint", item.first_joint);
    program.set("u_joint_count", item.joint_count);
    if (item.first_joint >= 0) {
        // Bound per item: other passes (the caustics, the gather) use storage bindings too.
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kJointMatricesBinding, item.joint_buffer);
    }
    glBindVertexArray(item.mesh->vertex_array.id());
}

void cull_as_material(const DrawItem& item, const DrawMaterial& material) {
    if (material.double_sided) {
        glDisable(GL_CULL_FACE);
        return;
    }
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    // glTF's front faces wind counter-clockwise; a mirroring transform turns them clockwise.
    glFrontFace(item.mirrored ? GL_CW : GL_CCW);
}

}  // namespace luxel::renderer
