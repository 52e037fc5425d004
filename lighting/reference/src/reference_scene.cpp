#include "luxel/lighting/reference/reference_scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include <glm/gtc/constants.hpp>

#include "luxel/lighting/core/illumination_maps.hpp"
#include "luxel/lighting/core/photon_world.hpp"
#include "luxel/lighting/reference/hit_textures.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/scene/texel_coverage.hpp"

namespace luxel::lighting::reference {
namespace {

glm::vec3 to_world(const glm::mat4& transform, const glm::vec3& p) {
    return glm::vec3(transform * glm::vec4(p, 1.0f));
}

/// Sub-points per texel edge at which a texel's open part is measured (kSub^2 per texel).
constexpr int kSub = 8;
enum : std::uint8_t { kUnknown = 0, kOpen = 1, kHidden = 2 };

/// The barycentric coordinates of `q` in the triangle `uv`; all negative for a degenerate one.
glm::dvec3 barycentric(const std::array<glm::dvec2, 3>& uv, const glm::dvec2& q) {
    const glm::dvec2 e1 = uv[1] - uv[0];
    const glm::dvec2 e2 = uv[2] - uv[0];
    const glm::dvec2 d = q - uv[0];
    const double det = e1.x * e2.y - e1.y * e2.x;
    if (!(std::abs(det) > 0.0)) {
        return glm::dvec3(-1.0);
    }
    const double b1 = (d.x * e2.y - d.y * e2.x) / det;
    const double b2 = (e1.x * d.y - e1.y * d.x) / det;
    return {1.0 - b1 - b2, b1, b2};
}

/// Whether a point of a light-mapped surface (world space, unit front normal `n`) is hidden by
/// an object resting on the surface: a surface within half a texel (`near`) straight above it,
/// as under a box standing on a bumpy floor, or the point inside a closed object: its normal
/// meets a face from behind, and four rays 60 degrees off it each meet one too or a face within
/// `near`, as under a crate whose bottom face lies in the floor's plane (or cuts through its
/// bumps). One back face is not enough: a floor under a roof modelled facing
/// the sky sees the roof from behind and the walls around from the front. Glass and water
/// (dielectric faces) enclose nothing: light passes through them, so the floor of a pool under
/// its water sheet, which sees the sheet from behind at every angle, stays open.
bool hidden_point(const RayScene& rays, std::span<const TraceMaterial> materials,
                  const glm::vec3& p, const glm::vec3& n, float near) {
    const glm::vec3 origin = offset_ray_origin(p, n);
    const std::optional<RayHit> up = rays.intersect(origin, n);
    if (!up) {
        return false;
    }
    const auto from_behind = [&](const glm::vec3& d, const std::optional<RayHit>& hit) {
        return hit && glm::dot(hit->geometric_normal, d) > 0.0f &&
               !(hit->material < materials.size() &&
                 materials[hit->material].scattering == Scattering::Dielectric);
    };
    if (!from_behind(n, up)) {
        return up->distance < near;
    }
    const glm::vec3 t = glm::normalize(
        glm::cross(n, std::abs(n.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0)));
    const glm::vec3 b = glm::cross(n, t);
    constexpr float kCos = 0.5f;  // cos 60 degrees
    constexpr float kSin = 0.8660254f;
    for (const glm::vec3& side : {t, -t, b, -b}) {
        // Closed that way: a face from behind, or any face within `near` (the bumps of a
        // floor inside the object).
        const glm::vec3 d = kCos * n + kSin * side;
        const std::optional<RayHit> hit = rays.intersect(origin, d);
        if (!from_behind(d, hit) && !(hit && hit->distance < near)) {
            return false;
        }
    }
    return true;
}

/// Hash-grid key of a point quantised to `cell`.
std::uint64_t cell_key(const glm::dvec3& p, double cell, const glm::ivec3& offset) {
    const auto q = [&](double v, int o) {
        return static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(v / cell)) + o);
    };
    std::uint64_t key = q(p.x, offset.x) * 0x9E3779B97F4A7C15ull;
    key ^= q(p.y, offset.y) * 0xC2B2AE3D27D4EB4Full + (key << 6) + (key >> 2);
    key ^= q(p.z, offset.z) * 0x165667B19E3779F9ull + (key << 6) + (key >> 2);
    return key;
}

glm::vec3 intensity_of(const LightSource& light) {
    constexpr double kFourPi = 4.0 * glm::pi<double>();
    switch (light.kind) {
        case LightKind::Point:
            return glm::vec3(glm::dvec3(light.power) / kFourPi);
        case LightKind::Spot: {
            const double cos_outer = std::cos(
                std::clamp(static_cast<double>(light.outer_cone), 1e-6, glm::pi<double>()));
            const double solid_angle = 2.0 * glm::pi<double>() * (1.0 - cos_outer);
            return solid_angle > 0.0 ? glm::vec3(glm::dvec3(light.power) / solid_angle)
                                     : glm::vec3(0.0f);
        }
        default:
            return glm::vec3(0.0f);
    }
}

}  // namespace

ReferenceScene::ReferenceScene(const RayScene& rays, std::vector<TraceMaterial> materials,
                               std::vector<LightSource> lights,
                               std::vector<ReferenceSurface> surfaces)
    : rays_(&rays), materials_(std::move(materials)), surfaces_(std::move(surfaces)) {
    for (ObjectId object : rays_->objects()) {
        for (std::uint32_t material : rays_->mesh(object).material_ids) {
            if (material >= materials_.size()) {
                throw Error("ReferenceScene: object " + std::to_string(object) +
                            " names material " + std::to_string(material) + " of " +
                            std::to_string(materials_.size()));
            }
        }
    }
    for (LightSource& source : lights) {
        ReferenceLight light;
        if (source.kind == LightKind::Area) {
            light.triangles = TriangleSampler(source.triangles, source.pieces);
        }
        if (source.kind == LightKind::Sky && !source.portals.empty()) {
            light.portals = TriangleSampler(source.portals);
        }
        light.intensity = intensity_of(source);
        light.source = std::move(source);
        lights_.push_back(std::move(light));
    }
    const glm::vec3 lo = rays_->bounds_min();
    const glm::vec3 hi = rays_->bounds_max();
    if (lo.x <= hi.x) {
        bounds_ = {0.5f * (lo + hi), std::max(0.5f * glm::length(hi - lo), 1e-6f)};
    }
    for (ReferenceSurface& surface : surfaces_) {
        surface.first_texel = texel_count_;
        texel_count_ += surface.texels.size();
        if (surface.surface >= surface_slot_.size()) {
            surface_slot_.resize(surface.surface + 1, -1);
        }
        surface_slot_[surface.surface] = static_cast<std::int32_t>(&surface - surfaces_.data());
        auto& lookup = texel_lookup_.emplace_back();
        for (std::size_t i = 0; i < surface.texels.size(); ++i) {
            const ReferenceTexel& texel = surface.texels[i];
            lookup[static_cast<std::int64_t>(texel.y) * surface.page_size + texel.x] =
                static_cast<std::uint32_t>(surface.first_texel + i);
        }
    }
    find_emitters();
    find_specular_objects();
    measure_texels();
}

std::size_t ReferenceScene::count_texels(const IlluminationMaps& maps) {
    std::size_t count = 0;
    for (const MapSurface& surface : maps.surfaces()) {
        if (surface.texels.page_size > 0) {
            count += surface.texels.texels.size();
        }
    }
    return count;
}

ReferenceScene ReferenceScene::from_world(const PhotonWorld& world, const IlluminationMaps& maps) {
    std::vector<LightSource> lights;
    for (const LightPhotons* light : world.active_lights()) {
        lights.push_back(light->emitter().light());
    }
    std::vector<ReferenceSurface> surfaces;
    const auto mapped = maps.surfaces();
    for (std::uint32_t s = 0; s < mapped.size(); ++s) {
        const SurfaceTexels& texels = mapped[s].texels;
        const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(mapped[s].to_world)));
        if (texels.texels.empty() || texels.page_size <= 0) {
            continue;
        }
        const std::vector<GatherTexel> centres = maps.world_texels(s);
        ReferenceSurface surface;
        surface.surface = s;
        surface.page = texels.page;
        surface.page_size = texels.page_size;
        // Exactly the texels: growth by doubling would take up to twice what
        // ReferenceIntegrator::bytes_per_texel() allows for.
        surface.texels.reserve(centres.size());
        for (std::size_t i = 0; i < centres.size(); ++i) {
            ReferenceTexel texel;
            texel.position = centres[i].position;
            texel.normal = centres[i].normal;
            // The face the texel's point lies on, turned to the side the texel gathers from.
            const glm::vec3 face = normal_matrix * texels.texels[i].face_normal;
            const float length = glm::length(face);
            texel.geometric = length > 0.0f && std::isfinite(length) ? face / length : texel.normal;
            if (glm::dot(texel.geometric, texel.normal) < 0.0f) {
                texel.geometric = -texel.geometric;
            }
            texel.x = texels.texels[i].x;
            texel.y = texels.texels[i].y;
            surface.texels.push_back(texel);
        }
        surfaces.push_back(std::move(surface));
    }
    ReferenceScene scene(world.ray_scene(), world.materials(), std::move(lights),
                         std::move(surfaces));
    scene.textures_ = HitTextures::from_world(world);
    return scene;
}

glm::vec3 ReferenceScene::diffuse_albedo(const RayHit& hit, const TraceMaterial& material) const {
    if (textures_ != nullptr) {
        if (const std::optional<glm::vec3> textured = textures_->albedo(hit)) {
            return *textured;
        }
    }
    return material.albedo;
}

const ReferenceTexel& ReferenceScene::texel(std::size_t index) const {
    // Surfaces are few; texel counts per surface many: a binary search on first_texel.
    const auto found = std::upper_bound(
        surfaces_.begin(), surfaces_.end(), index,
        [](std::size_t i, const ReferenceSurface& s) { return i < s.first_texel; });
    if (found == surfaces_.begin() || index >= texel_count_) {
        throw Error("ReferenceScene: texel " + std::to_string(index) + " out of range");
    }
    const ReferenceSurface& surface = *std::prev(found);
    return surface.texels.at(index - surface.first_texel);
}

std::vector<double> ReferenceScene::texel_areas() const {
    std::vector<double> areas;
    areas.reserve(texel_count_);
    for (const ReferenceSurface& surface : surfaces_) {
        for (const ReferenceTexel& texel : surface.texels) {
            areas.push_back(texel.area);
        }
    }
    return areas;
}

EmitterHit ReferenceScene::emitter_of(const RayHit& hit) const {
    if (emitters_.empty()) {
        return {};
    }
    const auto found =
        emitters_.find((static_cast<std::uint64_t>(hit.object) << 32) | hit.triangle);
    return found == emitters_.end() ? EmitterHit{} : found->second;
}

ReferenceScene::Emission ReferenceScene::emission_at(const EmitterHit& emitter,
                                                     const glm::vec3& point) const {
    if (emitter.light < 0 || static_cast<std::size_t>(emitter.light) >= lights_.size()) {
        return {};
    }
    const ReferenceLight& light = lights_[static_cast<std::size_t>(emitter.light)];
    const std::uint32_t piece = light.triangles.piece_at(emitter.triangle, point);
    return {area_radiance(light.source, emitter.triangle, piece),
            light.triangles.density(emitter.triangle, piece)};
}

std::int64_t ReferenceScene::texel_at(std::int32_t surface, const glm::vec2& uv) const {
    if (surface < 0 || static_cast<std::size_t>(surface) >= surface_slot_.size()) {
        return -1;
    }
    const std::int32_t slot = surface_slot_[static_cast<std::size_t>(surface)];
    if (slot < 0) {
        return -1;
    }
    const int size = surfaces_[static_cast<std::size_t>(slot)].page_size;
    const double u = static_cast<double>(uv.x) * size;
    const double v = static_cast<double>(uv.y) * size;
    if (!(u >= 0.0 && v >= 0.0 && u < size && v < size)) {
        return -1;
    }
    const auto key = static_cast<std::int64_t>(v) * size + static_cast<std::int64_t>(u);
    const auto& lookup = texel_lookup_[static_cast<std::size_t>(slot)];
    const auto found = lookup.find(key);
    return found == lookup.end() ? -1 : static_cast<std::int64_t>(found->second);
}

std::int64_t ReferenceScene::open_texel_at(std::int32_t surface, const glm::vec2& uv) const {
    const std::int64_t t = texel_at(surface, uv);
    if (t < 0) {
        return t;
    }
    // texel_at found the surface, so its page size is known; the sub-point is the fraction of
    // the way across the texel.
    const int size =
        surfaces_[static_cast<std::size_t>(surface_slot_[static_cast<std::size_t>(surface)])]
            .page_size;
    const double u = static_cast<double>(uv.x) * size;
    const double v = static_cast<double>(uv.y) * size;
    const int i = std::clamp(static_cast<int>((u - std::floor(u)) * kSub), 0, kSub - 1);
    const int j = std::clamp(static_cast<int>((v - std::floor(v)) * kSub), 0, kSub - 1);
    const std::size_t at =
        static_cast<std::size_t>(t) * kSub * kSub + static_cast<std::size_t>(j * kSub + i);
    return at < sub_points_.size() && sub_points_[at] == kHidden ? -1 : t;
}

void ReferenceScene::find_emitters() {
    // An area light arrives as world-space triangles; the ray scene reports (object,
    // triangle). They are matched by centroid in a hash grid whose cell is the tolerance, so
    // the float rounding of two different transform paths does not matter.
    const double tolerance = 1e-5 * std::max(static_cast<double>(bounds_.radius), 1e-6);
    std::unordered_multimap<std::uint64_t, std::pair<glm::dvec3, EmitterHit>> centroids;
    for (std::size_t l = 0; l < lights_.size(); ++l) {
        const auto& vertices = lights_[l].triangles.vertices();
        for (std::size_t t = 0; t + 2 < vertices.size(); t += 3) {
            const glm::dvec3 centre = (glm::dvec3(vertices[t]) + glm::dvec3(vertices[t + 1]) +
                                       glm::dvec3(vertices[t + 2])) /
                                      3.0;
            centroids.emplace(
                cell_key(centre, tolerance, glm::ivec3(0)),
                std::make_pair(centre, EmitterHit{static_cast<std::int32_t>(l),
                                                  static_cast<std::uint32_t>(t / 3)}));
        }
    }
    if (centroids.empty()) {
        return;
    }
    for (ObjectId object : rays_->objects()) {
        const TriangleMesh& mesh = rays_->mesh(object);
        const glm::mat4 transform = rays_->transform(object);
        for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
            glm::dvec3 centre(0.0);
            for (std::size_t k = 0; k < 3; ++k) {
                centre += glm::dvec3(to_world(transform, mesh.positions[mesh.indices[3 * t + k]]));
            }
            centre /= 3.0;
            for (int dz = -1; dz <= 1; ++dz) {
                for (int dy = -1; dy <= 1; ++dy) {
                    for (int dx = -1; dx <= 1; ++dx) {
                        const auto range =
                            centroids.equal_range(cell_key(centre, tolerance, {dx, dy, dz}));
                        for (auto it = range.first; it != range.second; ++it) {
                            if (glm::length(it->second.first - centre) <= tolerance) {
                                emitters_[(static_cast<std::uint64_t>(object) << 32) | t] =
                                    it->second.second;
                            }
                        }
                    }
                }
            }
        }
    }
}

void ReferenceScene::find_specular_objects() {
    for (ObjectId object : rays_->objects()) {
        const TriangleMesh& mesh = rays_->mesh(object);
        const glm::mat4 transform = rays_->transform(object);
        glm::vec3 lo(std::numeric_limits<float>::max());
        glm::vec3 hi(std::numeric_limits<float>::lowest());
        std::vector<glm::vec3> points;
        for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
            if (materials_[mesh.material_ids[t]].scattering == Scattering::Diffuse) {
                continue;
            }
            for (std::size_t k = 0; k < 3; ++k) {
                const glm::vec3 p = to_world(transform, mesh.positions[mesh.indices[3 * t + k]]);
                lo = glm::min(lo, p);
                hi = glm::max(hi, p);
                points.push_back(p);
            }
        }
        if (points.empty()) {
            continue;
        }
        const glm::vec3 centre = 0.5f * (lo + hi);
        float radius = 0.0f;
        for (const glm::vec3& p : points) {
            radius = std::max(radius, glm::length(p - centre));
        }
        // A hair larger, so photons grazing the outermost vertices are still aimed at.
        specular_.push_back({centre, std::max(radius * 1.0001f, 1e-6f)});
    }
}

void ReferenceScene::measure_texels() {
    // Areas: every light-mapped triangle's UV footprint clipped against the texel squares it
    // overlaps, scaled by the triangle's world-to-UV area ratio (exact for an affine map), times
    // the share of it a camera can see: of the kSub x kSub sub-points of the texel that lie in
    // the triangle, those no object rests on (hidden_point). A texel half under a box's edge
    // then counts half its area, and the photons binned in it (indirect_photons.cpp,
    // caustic_reference.cpp) give the light on its open half: what a player sees beside the
    // box, not that light averaged with the dark under it, which no view shows and which a
    // light map holding it would paint along the box's base as a dark band. Each sub-point is
    // tested once, whichever of the (possibly coincident) triangles over it comes first.
    sub_points_.assign(texel_count_ * kSub * kSub, kUnknown);
    for (ObjectId object : rays_->objects()) {
        const TriangleMesh& mesh = rays_->mesh(object);
        if (mesh.lightmap_uvs.size() != mesh.positions.size()) {
            continue;
        }
        const glm::mat4 transform = rays_->transform(object);
        for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
            const std::int32_t id = mesh.surface_ids[t];
            if (id < 0 || static_cast<std::size_t>(id) >= surface_slot_.size() ||
                surface_slot_[static_cast<std::size_t>(id)] < 0) {
                continue;
            }
            const auto slot = static_cast<std::size_t>(surface_slot_[static_cast<std::size_t>(id)]);
            ReferenceSurface& surface = surfaces_[slot];
            const double size = surface.page_size;
            std::array<glm::dvec3, 3> world{};
            std::array<glm::dvec2, 3> uv{};
            for (std::size_t k = 0; k < 3; ++k) {
                const std::uint32_t index = mesh.indices[3 * t + k];
                world[k] = glm::dvec3(to_world(transform, mesh.positions[index]));
                uv[k] = glm::dvec2(mesh.lightmap_uvs[index]) * size;
            }
            const double world_area =
                0.5 * glm::length(glm::cross(world[1] - world[0], world[2] - world[0]));
            const double uv_area = 0.5 * std::abs((uv[1].x - uv[0].x) * (uv[2].y - uv[0].y) -
                                                  (uv[1].y - uv[0].y) * (uv[2].x - uv[0].x));
            if (!(uv_area > 0.0) || !(world_area > 0.0)) {
                continue;
            }
            const double scale = world_area / uv_area;
            const glm::vec3 normal(
                glm::normalize(glm::cross(world[1] - world[0], world[2] - world[0])));
            const auto near = static_cast<float>(0.5 * std::sqrt(scale));  // half a texel
            // Clipped to the page: texels exist only there, and UVs far off it (a hostile file)
            // must not make the loop walk thousands of pages of nothing.
            const glm::dvec2 lo = glm::clamp(glm::min(uv[0], glm::min(uv[1], uv[2])),
                                             glm::dvec2(0.0), glm::dvec2(size));
            const glm::dvec2 hi = glm::clamp(glm::max(uv[0], glm::max(uv[1], uv[2])),
                                             glm::dvec2(0.0), glm::dvec2(size));
            const auto& lookup = texel_lookup_[slot];
            for (auto y = static_cast<int>(std::floor(lo.y)); y <= static_cast<int>(hi.y); ++y) {
                for (auto x = static_cast<int>(std::floor(lo.x)); x <= static_cast<int>(hi.x);
                     ++x) {
                    const auto found =
                        lookup.find(static_cast<std::int64_t>(y) * surface.page_size + x);
                    if (found == lookup.end()) {
                        continue;
                    }
                    const double inside = scene::triangle_area_in_texel(uv[0], uv[1], uv[2], x, y);
                    if (!(inside > 0.0)) {
                        continue;
                    }
                    // A sub-point on the triangle's edge is shared with the triangle across
                    // it: each counts it half (a quad's diagonal runs through texel corners). A
                    // sliver holding no sub-point (a finely meshed bumpy floor has many) takes
                    // the sub-point nearest its centroid, on its plane.
                    const glm::dvec2 centroid = (uv[0] + uv[1] + uv[2]) / 3.0;
                    const auto nearest_sub = [&](double c, int base) {
                        return std::clamp(static_cast<int>(std::floor((c - base) * kSub)), 0,
                                          kSub - 1);
                    };
                    const int fallback_i = nearest_sub(centroid.x, x);
                    const int fallback_j = nearest_sub(centroid.y, y);
                    const auto state_at = [&](int i, int j, const glm::dvec3& w) {
                        std::uint8_t& state =
                            sub_points_[static_cast<std::size_t>(found->second) * kSub * kSub +
                                        static_cast<std::size_t>(j * kSub + i)];
                        if (state == kUnknown) {
                            const glm::vec3 point(w.x * world[0] + w.y * world[1] + w.z * world[2]);
                            state = hidden_point(*rays_, materials_, point, normal, near) ? kHidden
                                                                                          : kOpen;
                        }
                        return state;
                    };
                    double in_triangle = 0.0;
                    double open = 0.0;
                    for (int j = 0; j < kSub; ++j) {
                        for (int i = 0; i < kSub; ++i) {
                            const glm::dvec2 q(x + (i + 0.5) / kSub, y + (j + 0.5) / kSub);
                            const glm::dvec3 w = barycentric(uv, q);
                            const double least = std::min(w.x, std::min(w.y, w.z));
                            if (!(least >= -1e-12)) {
                                continue;
                            }
                            const double weight = least > 1e-12 ? 1.0 : 0.5;
                            in_triangle += weight;
                            open += state_at(i, j, w) == kOpen ? weight : 0.0;
                        }
                    }
                    double seen = in_triangle > 0.0 ? open / in_triangle : 1.0;
                    if (!(in_triangle > 0.0)) {
                        const glm::dvec2 q(x + (fallback_i + 0.5) / kSub,
                                           y + (fallback_j + 0.5) / kSub);
                        seen = state_at(fallback_i, fallback_j, barycentric(uv, q)) == kOpen ? 1.0
                                                                                             : 0.0;
                    }
                    surface.texels[found->second - surface.first_texel].area +=
                        inside * scale * seen;
                }
            }
        }
    }
    // The face under each texel comes with the texel (ReferenceTexel::geometric, from the
    // triangle its point lies on). It was once found by a short ray down the texel normal,
    // which costs a traversal of every triangle stacked at that point: 5,000 coincident
    // triangles took 77 s to load.
}

}  // namespace luxel::lighting::reference
