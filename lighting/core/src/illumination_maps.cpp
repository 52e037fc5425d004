#include "luxel/lighting/core/illumination_maps.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <glm/gtc/constants.hpp>

#include "iim_pass_filter.hpp"
#include "luxel/ecs/hierarchy.hpp"
#include "luxel/lighting/core/light_source.hpp"
#include "luxel/lighting/core/ray_scene.hpp"
#include "luxel/scene/image_decode.hpp"

namespace luxel::lighting {
namespace {

bool finite_vector(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// A value fit for a light map: finite and non-negative per channel.
glm::vec3 sanitized(const glm::vec3& v) {
    return finite_vector(v) ? glm::max(v, glm::vec3(0.0f)) : glm::vec3(0.0f);
}

glm::mat4 world_matrix(const ecs::Registry& registry, ecs::Entity entity) {
    if (const auto* world = registry.try_get<ecs::WorldTransform>(entity)) {
        return world->matrix;
    }
    return ecs::compute_world_matrix(registry, entity);
}

/// A relative delta, guarded: a surface holding nothing has changed "completely" when anything
/// arrived, and not at all otherwise.
double relative(double delta, double stored) {
    if (stored > 0.0) {
        return delta / stored;
    }
    return delta > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
}

double safe_area(double area) {
    return area > 1e-12 ? area : 1e-12;
}

}  // namespace

IlluminationMaps::IlluminationMaps(ecs::Registry& registry, PhotonWorld& world,
                                   IlluminationSettings settings)
    : registry_(registry),
      world_(world),
      settings_(settings),
      moves_(registry.observe<ecs::WorldTransform>()),
      area_changes_(registry.observe<AreaLight>()) {
    sync();
}

/// A rebuild in progress: the surface's kd-tree (the only one in memory) and where it got to.
struct IlluminationMaps::AimPass {
    std::uint32_t surface = 0;
    std::unique_ptr<PhotonDensity> density;
    std::vector<GatherTexel> texels;  ///< world space, at the pass's start
    std::size_t cursor = 0;
};

IlluminationMaps::~IlluminationMaps() = default;

std::int32_t IlluminationMaps::page_index(const scene::Scene* source, int page, int page_size) {
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

void IlluminationMaps::add_surface(std::uint32_t surface) {
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
                mapped.material_emission = sanitized(material.emitted_radiance());
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
    mapped.gather_cursor = mapped.texels.texels.size();
    surfaces_.push_back(std::move(mapped));
    surfaces_of_[info.entity].push_back(surface);
    refresh_transform(surface);
    if (refresh_emission(surface)) {
        ++emission_version_;
    }
}

bool IlluminationMaps::refresh_emission(std::uint32_t surface) {
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

void IlluminationMaps::refresh_transform(std::uint32_t surface) {
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
}

void IlluminationMaps::sync() {
    for (auto s = static_cast<std::uint32_t>(surfaces_.size()); s < world_.surfaces().size(); ++s) {
        add_surface(s);
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
        }
    });
}

std::vector<GatherTexel> IlluminationMaps::world_texels(std::uint32_t surface) const {
    const MapSurface& mapped = surfaces_.at(surface);
    const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(mapped.to_world)));
    std::vector<GatherTexel> texels;
    texels.reserve(mapped.texels.texels.size());
    for (const SurfaceTexel& texel : mapped.texels.texels) {
        GatherTexel world;
        world.position = glm::vec3(mapped.to_world * glm::vec4(texel.position, 1.0f));
        const glm::vec3 n = normal_matrix * texel.normal;
        const float length = glm::length(n);
        world.normal = length > 0.0f && std::isfinite(length) ? n / length : texel.normal;
        texels.push_back(world);
    }
    return texels;
}

bool IlluminationMaps::needs_aim(std::uint32_t s) const {
    const PhotonMap& map = world_.photon_map();
    const MapSurface& mapped = surfaces_[s];
    if (mapped.texels.texels.empty() || !registry_.valid(mapped.entity) ||
        s >= map.surface_count()) {
        return false;
    }
    const SurfacePhotons& photons = map.surface(s);
    const double change = relative(photons.delta_full.value(), photons.stored_energy.value());
    const bool in_progress = aim_pass_ && aim_pass_->surface == s;
    return !mapped.aim_built || in_progress || change > settings_.aim_threshold;
}

bool IlluminationMaps::aims_current() const {
    for (std::uint32_t s = 0; s < surfaces_.size(); ++s) {
        if (needs_aim(s)) {
            return false;
        }
    }
    return true;
}

std::vector<MapRequest> IlluminationMaps::aim_requests() const {
    std::vector<MapRequest> requests;
    const PhotonMap& map = world_.photon_map();
    for (std::uint32_t s = 0; s < surfaces_.size(); ++s) {
        if (needs_aim(s)) {
            const MapSurface& mapped = surfaces_[s];
            const double delta = map.surface(s).delta_full.value();
            const bool first = !mapped.aim_built;
            const bool in_progress = aim_pass_ && aim_pass_->surface == s;
            // The pass in progress, then unbuilt maps, then the surfaces whose light changed
            // most per square metre.
            double priority = delta / safe_area(mapped.texels.area);
            if (first) {
                priority = std::numeric_limits<double>::max() / 2.0;
            }
            if (in_progress) {
                priority = std::numeric_limits<double>::max();
            }
            requests.push_back({s, priority});
        }
    }
    std::stable_sort(
        requests.begin(), requests.end(),
        [](const MapRequest& l, const MapRequest& r) { return l.priority > r.priority; });
    return requests;
}

std::size_t IlluminationMaps::rebuild_aim(std::uint32_t surface, std::size_t max_texels) {
    MapSurface& mapped = surfaces_.at(surface);
    const std::int32_t page_id = aim_.surface_page.at(surface);
    PhotonMap& map = world_.photon_map();
    if (page_id < 0 || surface >= map.surface_count() || max_texels == 0) {
        return 0;
    }
    if (aim_pass_ && aim_pass_->surface != surface) {
        // One tree at a time: the pass in progress goes on (this call's effort goes to it), so
        // passes finish in order however the requests interleave. Only a pass whose surface
        // went away is dropped.
        if (registry_.valid(surfaces_[aim_pass_->surface].entity)) {
            return rebuild_aim(aim_pass_->surface, max_texels);
        }
        aim_pass_.reset();
    }
    if (!aim_pass_) {
        aim_pass_ = std::make_unique<AimPass>();
        aim_pass_->surface = surface;
        const std::array<std::uint32_t, 1> sources{surface};
        aim_pass_->density = std::make_unique<PhotonDensity>(map, sources, PhotonSelection::Full);
        aim_pass_->texels = world_texels(surface);
        // Photons that change from now on need another pass; this one sees the tree's snapshot.
        map.reset_full_delta(surface);
    }
    AimPass& pass = *aim_pass_;
    RadiancePage& page = aim_.pages[static_cast<std::size_t>(page_id)];
    const double metres_per_texel = mapped.world_metres_per_texel;
    DensitySettings density = settings_.density;
    if (metres_per_texel > 0.0 && settings_.max_radius_texels > 0.0f) {
        density.max_radius =
            static_cast<float>(static_cast<double>(settings_.max_radius_texels) * metres_per_texel);
    }
    const std::size_t first = pass.cursor;
    const std::size_t end = std::min(pass.texels.size(), first + max_texels);
    int x0 = page.size;
    int y0 = page.size;
    int x1 = -1;
    int y1 = -1;
    const float probe_length =
        static_cast<float>(settings_.enclosure_probe_texels * metres_per_texel);
    for (std::size_t i = first; i < end; ++i) {
        const SurfaceTexel& texel = mapped.texels.texels[i];
        glm::vec3 radiance(0.0f);
        if (probe_length > 0.0f && enclosed(pass.texels[i], probe_length)) {
            page.at(texel.x, texel.y) = radiance;
            ++counters_.enclosed_texels;
            x0 = std::min(x0, texel.x);
            y0 = std::min(y0, texel.y);
            x1 = std::max(x1, texel.x);
            y1 = std::max(y1, texel.y);
            continue;
        }
        const DensitySample found =
            pass.density->sample(pass.texels[i].position, pass.texels[i].normal, density);
        if (found.radius > 0.0 && metres_per_texel > 0.0) {
            const double on_surface = mapped.footprint.fraction(i, found.radius / metres_per_texel,
                                                                settings_.density.kernel);
            const double area = glm::pi<double>() * found.radius * found.radius * on_surface;
            radiance =
                glm::vec3(glm::dvec3(mapped.albedo) * found.power / (area * glm::pi<double>()));
        }
        page.at(texel.x, texel.y) = sanitized(radiance);
        x0 = std::min(x0, texel.x);
        y0 = std::min(y0, texel.y);
        x1 = std::max(x1, texel.x);
        y1 = std::max(y1, texel.y);
    }
    pass.cursor = end;
    const bool complete = pass.cursor >= pass.texels.size();
    if (complete) {
        dilate(surface, page);
        // The padding ring around the whole surface was written too.
        for (const SurfaceTexel& texel : mapped.texels.texels) {
            x0 = std::min(x0, texel.x - 1);
            y0 = std::min(y0, texel.y - 1);
            x1 = std::max(x1, texel.x + 1);
            y1 = std::max(y1, texel.y + 1);
        }
    }
    if (x1 >= x0) {
        x0 = std::max(x0, 0);
        y0 = std::max(y0, 0);
        x1 = std::min(x1, page.size - 1);
        y1 = std::min(y1, page.size - 1);
        page.mark_dirty({x0, y0, x1 - x0 + 1, y1 - y0 + 1});
    }
    counters_.aim_texels += end - first;
    if (complete) {
        mapped.aim_built = true;
        ++counters_.aim_rebuilds;
        aim_pass_.reset();
    }
    return end - first;
}

bool IlluminationMaps::enclosed(const GatherTexel& texel, float probe_length) const {
    // Rays over the hemisphere: the normal and eight cosine-distributed directions around it.
    // A texel under an object resting on its surface has (nearly) all of them blocked within a
    // texel or two; one in a corner or beside a wall has the ones pointing away free (half or
    // more). Two free rays are allowed: where a box rests on a bumpy floor, grazing rays slip
    // out through the gaps between the bumps although hardly any light gets in.
    constexpr int kProbes = 9;
    constexpr int kFreeAllowed = 2;
    const RayScene& scene = world_.ray_scene();
    const glm::vec3 origin = offset_ray_origin(texel.position, texel.normal);
    int free = 0;
    for (int k = 0; k < kProbes && free <= kFreeAllowed; ++k) {
        const glm::vec3 direction =
            k == 0 ? texel.normal
                   : cosine_direction(
                         texel.normal,
                         glm::dvec2((static_cast<double>(k) - 0.5) / (kProbes - 1),
                                    std::fmod(static_cast<double>(k) * 0.6180339887498949, 1.0)));
        free += scene.occluded(origin, direction, probe_length) ? 0 : 1;
    }
    return free <= kFreeAllowed;
}

void IlluminationMaps::dilate(std::uint32_t surface, RadiancePage& page) const {
    const MapSurface& mapped = surfaces_[surface];
    const auto& owners = owners_[static_cast<std::size_t>(aim_.surface_page[surface])];
    const int size = page.size;
    const auto owner = [&](int x, int y) {
        return owners[static_cast<std::size_t>(y) * static_cast<std::size_t>(size) +
                      static_cast<std::size_t>(x)];
    };
    const auto self = static_cast<std::int32_t>(surface);
    for (const SurfaceTexel& texel : mapped.texels.texels) {
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                const int x = texel.x + dx;
                const int y = texel.y + dy;
                if (x < 0 || y < 0 || x >= size || y >= size || owner(x, y) >= 0) {
                    continue;
                }
                // The mean of this surface's texels around the padding texel.
                glm::vec3 sum(0.0f);
                int count = 0;
                for (int ny = std::max(y - 1, 0); ny <= std::min(y + 1, size - 1); ++ny) {
                    for (int nx = std::max(x - 1, 0); nx <= std::min(x + 1, size - 1); ++nx) {
                        if (owner(nx, ny) == self) {
                            sum += page.at(nx, ny);
                            ++count;
                        }
                    }
                }
                page.at(x, y) = count > 0 ? sum / static_cast<float>(count) : glm::vec3(0.0f);
            }
        }
    }
}

bool IlluminationMaps::aims_ready() const {
    // A pass started before every lit surface has an AIM would gather black where the AIM is
    // missing and consume the delta_i that should have brought it back.
    const PhotonMap& map = world_.photon_map();
    for (std::uint32_t s = 0; s < surfaces_.size() && s < map.surface_count(); ++s) {
        if (!surfaces_[s].aim_built && !surfaces_[s].texels.texels.empty() &&
            map.surface(s).stored_energy.value() > 0.0) {
            return false;
        }
    }
    return true;
}

bool IlluminationMaps::lighting_changed(std::uint32_t s, bool aims_are_current) const {
    const SurfacePhotons& photons = world_.photon_map().surface(s);
    const MapSurface& mapped = surfaces_[s];
    // An area light's emission changed: its direct light on every surface comes from the
    // gather, so every surface gathers again.
    return relative(photons.delta_indirect.value(), photons.stored_energy.value()) >
               settings_.iim_threshold ||
           mapped.gathered_emission != emission_version_ ||
           (mapped.gathered_stale && aims_are_current);
}

bool IlluminationMaps::wants_refinement(std::uint32_t s) const {
    const MapSurface& mapped = surfaces_[s];
    return refine_ && mapped.gathered_once && !mapped.gathered_stale &&
           mapped.passes_averaged < settings_.refine_passes;
}

std::vector<MapRequest> IlluminationMaps::gather_requests() const {
    std::vector<MapRequest> requests;
    const PhotonMap& map = world_.photon_map();
    const bool ready = aims_ready();
    const bool current = aims_current();
    for (std::uint32_t s = 0; s < surfaces_.size(); ++s) {
        const MapSurface& mapped = surfaces_[s];
        if (mapped.texels.texels.empty() || !registry_.valid(mapped.entity) ||
            s >= map.surface_count()) {
            continue;
        }
        const double delta = map.surface(s).delta_indirect.value();
        const bool changed = lighting_changed(s, current);
        // Refinement only over current AIMs: an average of passes over different AIMs would
        // mix old light into new.
        const bool refine = !changed && current && wants_refinement(s);
        if (mapped.gather_in_progress || (ready && (!mapped.gathered_once || changed || refine))) {
            // Passes in progress first, the furthest along first, so passes finish one after
            // another instead of all crawling together (a pass shows only when complete); then
            // surfaces never gathered; then the largest delta_i / area; refinement last: a
            // refinement pass in progress, then the surfaces with the fewest passes averaged.
            // A change never waits for refinement (a refinement pass of a surface whose light
            // changed is dropped and started afresh by gather()).
            const double done = static_cast<double>(mapped.gather_cursor) /
                                static_cast<double>(mapped.texels.texels.size());
            double priority = delta / safe_area(mapped.texels.area);
            if (mapped.gather_in_progress && !mapped.pass_refines) {
                priority = std::numeric_limits<double>::max() / 2.0 * (1.0 + done);
            } else if (!mapped.gathered_once) {
                priority = std::numeric_limits<double>::max() / 4.0;
            } else if (!changed && mapped.gather_in_progress) {
                priority = -0.5 + 0.25 * done;
            } else if (!changed) {
                priority = -static_cast<double>(mapped.passes_averaged);
            }
            requests.push_back({s, priority});
        }
    }
    std::stable_sort(
        requests.begin(), requests.end(),
        [](const MapRequest& l, const MapRequest& r) { return l.priority > r.priority; });
    return requests;
}

std::size_t IlluminationMaps::gather(std::uint32_t surface, std::size_t max_texels,
                                     IrradianceGatherer& gatherer, double now_seconds) {
    MapSurface& mapped = surfaces_.at(surface);
    const std::int32_t page_id = aim_.surface_page.at(surface);
    if (page_id < 0 || mapped.texels.texels.empty() || max_texels == 0) {
        return 0;
    }
    if (mapped.gather_in_progress && mapped.pass_refines &&
        lighting_changed(surface, aims_current())) {
        mapped.gather_in_progress = false;  // the light changed under a refinement pass
        filters_.erase(surface);
    }
    if (!mapped.gather_in_progress && !aims_ready()) {
        // Checked again here, not only when the request was made: photons stored since (by
        // retraces earlier in the same frame) may have made a surface lit without an AIM.
        return 0;
    }
    const std::size_t total = mapped.texels.texels.size();
    if (!mapped.gather_in_progress) {
        // Changes from now on need another pass; those before are what this pass sees.
        mapped.gather_in_progress = true;
        mapped.gather_cursor = 0;
        mapped.pass_irradiance.assign(total, glm::vec3(0.0f));
        const bool current = aims_current();
        mapped.pass_refines = mapped.gathered_once && !lighting_changed(surface, current) &&
                              current && wants_refinement(surface);
        ++mapped.passes_started;
        mapped.gathered_emission = emission_version_;
        mapped.pass_aim_rebuilds = counters_.aim_rebuilds;
        mapped.gathered_stale = !current;
        world_.photon_map().reset_indirect_delta(surface);
        ++counters_.gather_passes;
    }
    const std::size_t first = mapped.gather_cursor;
    const std::size_t count = std::min(max_texels, total - first);
    if (count > 0) {
        std::vector<GatherTexel> all = world_texels(surface);
        for (GatherTexel& texel : all) {
            texel.pass = mapped.passes_started;
        }
        const std::span<const GatherTexel> batch(all.data() + first, count);
        gatherer.gather(batch, std::span<glm::vec3>(mapped.pass_irradiance.data() + first, count));
        mapped.gather_cursor = first + count;
        counters_.texels_gathered += count;
        if (mapped.gather_cursor >= total) {
            begin_filter(surface);
        }
    }
    // Filtering a texel costs about a fortieth of gathering it with 64 rays: what is left of
    // this call's texels goes to the filter at that rate, so a call that gathers the last
    // texels of a large surface does not also filter all of it.
    constexpr std::size_t kFilteredPerGathered = 32;
    if (const auto filter = filters_.find(surface); filter != filters_.end()) {
        filter->second->run((max_texels - count) * kFilteredPerGathered);
        if (filter->second->done()) {
            finish_pass(surface, now_seconds);
        }
    }
    return count;
}

/// A completed pass's values go into the surface's mean (refinement) and a filter starts over
/// them: a tent of radius iim_filter_radius texels over the surface's own texels (final
/// gathering's noise is per texel while indirect light varies slowly, so a small filter removes
/// most of the noise for little bias), noise-aware from the third pass. The filter runs in
/// slices (gather() gives it the budget its call has left), then finish_pass() fades it in.
void IlluminationMaps::begin_filter(std::uint32_t surface) {
    MapSurface& mapped = surfaces_[surface];
    const std::size_t count = mapped.texels.texels.size();
    const bool refining = mapped.pass_refines && mapped.passes_averaged > 0 &&
                          mapped.mean_irradiance.size() == count &&
                          mapped.irradiance_m2.size() == count;
    mapped.pass_passes = refining ? mapped.passes_averaged + 1 : 1;
    const std::uint32_t passes = mapped.pass_passes;
    // The per-texel mean of the passes (unfiltered) and, for the noise estimate, the sum of
    // squared deviations (Welford's update, in double per step so long runs do not drift).
    // Kept only while more passes may be averaged in.
    const bool keep_mean = refine_ && settings_.refine_passes > 1;
    std::vector<glm::vec3> values(count);
    if (keep_mean) {
        mapped.mean_irradiance.resize(count);
        mapped.irradiance_m2.resize(count);
        for (std::size_t i = 0; i < count; ++i) {
            const glm::dvec3 x(sanitized(mapped.pass_irradiance[i]));
            if (!refining) {
                mapped.mean_irradiance[i] = glm::vec3(x);
                mapped.irradiance_m2[i] = glm::vec3(0.0f);
            } else {
                const glm::dvec3 old_mean(mapped.mean_irradiance[i]);
                const glm::dvec3 mean = old_mean + (x - old_mean) / static_cast<double>(passes);
                mapped.mean_irradiance[i] = glm::vec3(mean);
                mapped.irradiance_m2[i] =
                    glm::vec3(glm::dvec3(mapped.irradiance_m2[i]) + (x - old_mean) * (x - mean));
            }
            values[i] = mapped.mean_irradiance[i];
        }
    } else {
        mapped.mean_irradiance = {};
        mapped.irradiance_m2 = {};
        for (std::size_t i = 0; i < count; ++i) {
            values[i] = sanitized(mapped.pass_irradiance[i]);
        }
    }
    // With three passes or more each texel knows its noise: the variance of its mean, summed
    // over the channels. The filter then leaves out neighbours whose difference is not
    // explained by the noise (a range weight, as a bilateral filter's, in units of the noise):
    // noise is smoothed, while a real feature such as the focus of light under a glass sphere
    // (one texel, several times its neighbours) keeps its value. Fewer passes: the plain tent.
    const double sigmas = static_cast<double>(settings_.iim_filter_noise_sigmas);
    std::vector<double> noise;
    if (sigmas > 0.0 && passes >= 3 && keep_mean) {
        noise.resize(count);
        const double scale = 1.0 / (static_cast<double>(passes - 1) * static_cast<double>(passes));
        for (std::size_t i = 0; i < count; ++i) {
            const glm::dvec3 m2(mapped.irradiance_m2[i]);
            noise[i] = (m2.x + m2.y + m2.z) * scale;
        }
    }
    filters_[surface] =
        std::make_unique<IimPassFilter>(mapped.texels.texels, std::move(values), std::move(noise),
                                        settings_.iim_filter_radius, sigmas);
    mapped.pass_irradiance.clear();
    mapped.pass_irradiance.shrink_to_fit();
}

void IlluminationMaps::finish_pass(std::uint32_t surface, double now_seconds) {
    MapSurface& mapped = surfaces_[surface];
    const auto found = filters_.find(surface);
    if (found == filters_.end()) {
        return;
    }
    const IimPassFilter& filter = *found->second;
    if (counters_.aim_rebuilds != mapped.pass_aim_rebuilds) {
        mapped.gathered_stale = true;  // an AIM changed under the pass
    }
    const auto page_id = static_cast<std::size_t>(aim_.surface_page[surface]);
    IimPage& page = iim_pages_[page_id];
    const auto& texels = mapped.texels.texels;
    const std::vector<glm::vec3>& filtered = filter.filtered();
    for (std::size_t i = 0; i < texels.size() && i < filtered.size(); ++i) {
        const glm::vec3 e = filtered[i];
        const glm::vec3 value = mapped.content == IimContent::Irradiance
                                    ? e
                                    : mapped.albedo * e * glm::one_over_pi<float>();
        page.commit(texels[i].x, texels[i].y, value, now_seconds, settings_.blend_seconds);
    }
    // Fill the padding so bilinear lookups at the border hold.
    const auto& owners = owners_[page_id];
    const int size = page.current.size;
    for (const SurfaceTexel& texel : texels) {
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                const int x = texel.x + dx;
                const int y = texel.y + dy;
                if (x < 0 || y < 0 || x >= size || y >= size ||
                    owners[static_cast<std::size_t>(y) * static_cast<std::size_t>(size) +
                           static_cast<std::size_t>(x)] >= 0) {
                    continue;
                }
                page.commit(x, y, page.current.at(texel.x, texel.y), now_seconds,
                            settings_.blend_seconds);
            }
        }
    }
    const glm::ivec4 bounds = filter.bounds();
    const int left = std::max(bounds.x - 1, 0);
    const int top = std::max(bounds.y - 1, 0);
    page.current.mark_dirty(
        {left, top, std::min(bounds.z + 2, size) - left, std::min(bounds.w + 2, size) - top});
    mapped.passes_averaged = mapped.pass_passes;
    if (mapped.passes_averaged >= settings_.refine_passes) {
        // Done refining: the IIM holds the filtered mean.
        mapped.mean_irradiance = {};
        mapped.irradiance_m2 = {};
    }
    mapped.gather_in_progress = false;
    mapped.gathered_once = true;
    filters_.erase(found);
}

}  // namespace luxel::lighting
