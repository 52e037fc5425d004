#include "aim_rebuilder.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <glm/gtc/constants.hpp>

#include "luxel/lighting/core/ray_scene.hpp"
#include "map_support.hpp"

namespace luxel::lighting {

using namespace map_support;

/// A rebuild in progress: the surface's kd-tree (the only one in memory) and where it got to.
struct AimRebuilder::RebuildState {
    std::uint32_t surface = 0;
    std::unique_ptr<PhotonDensity> density;
    std::vector<GatherTexel> texels;  ///< world space, at the rebuild's start
    std::size_t cursor = 0;
};

AimRebuilder::AimRebuilder(MapRegistry& registry, const PhotonWorld& world, SurfaceDeltas& deltas,
                           const IlluminationSettings& settings)
    : registry_(registry), world_(world), deltas_(deltas), settings_(settings) {}

AimRebuilder::~AimRebuilder() = default;

bool AimRebuilder::needs_rebuild(std::uint32_t s) const {
    const PhotonMap& map = world_.photon_map();
    if (!registry_.live(s) || s >= map.surface_count()) {
        return false;
    }
    const SurfacePhotons& photons = map.surface(s);
    const double change = relative(deltas_.full(map, s), photons.stored_energy.value());
    const bool in_progress = rebuild_ && rebuild_->surface == s;
    return !built(s) || in_progress || change > settings_.aim_threshold;
}

bool AimRebuilder::current() const {
    for (std::uint32_t s = 0; s < registry_.surfaces().size(); ++s) {
        if (needs_rebuild(s)) {
            return false;
        }
    }
    return true;
}

double AimRebuilder::priority(std::uint32_t s) const {
    const MapSurface& mapped = registry_.surface(s);
    // The rebuild in progress, then unbuilt maps, then the surfaces whose light changed most per
    // square metre.
    if (rebuild_ && rebuild_->surface == s) {
        return std::numeric_limits<double>::max();
    }
    if (!built(s)) {
        return std::numeric_limits<double>::max() / 2.0;
    }
    return deltas_.full(world_.photon_map(), s) / safe_area(mapped.texels.area);
}

std::vector<MapRequest> AimRebuilder::requests() const {
    std::vector<MapRequest> requests;
    for (std::uint32_t s = 0; s < registry_.surfaces().size(); ++s) {
        if (needs_rebuild(s)) {
            requests.push_back({s, priority(s)});
        }
    }
    std::stable_sort(
        requests.begin(), requests.end(),
        [](const MapRequest& l, const MapRequest& r) { return l.priority > r.priority; });
    return requests;
}

std::optional<std::uint32_t> AimRebuilder::next_surface() const {
    std::optional<std::uint32_t> best;
    double best_priority = 0.0;
    for (std::uint32_t s = 0; s < registry_.surfaces().size(); ++s) {
        if (needs_rebuild(s)) {
            // Strictly greater: the first of equals, as requests()'s stable sort puts it.
            const double candidate = priority(s);
            if (!best || candidate > best_priority) {
                best = s;
                best_priority = candidate;
            }
        }
    }
    return best;
}

std::size_t AimRebuilder::rebuild(std::uint32_t surface, std::size_t max_texels) {
    const MapSurface& mapped = registry_.surface(surface);
    const std::int32_t page_id = registry_.page_of(surface);
    const PhotonMap& map = world_.photon_map();
    if (page_id < 0 || surface >= map.surface_count() || max_texels == 0) {
        return 0;
    }
    if (rebuild_ && rebuild_->surface != surface) {
        // One tree at a time: the rebuild in progress goes on (this call's effort goes to it), so
        // rebuilds finish in order however the requests interleave. Only a rebuild whose surface
        // went away is dropped.
        if (registry_.live(rebuild_->surface)) {
            return rebuild(rebuild_->surface, max_texels);
        }
        rebuild_.reset();
    }
    if (!rebuild_) {
        rebuild_ = std::make_unique<RebuildState>();
        rebuild_->surface = surface;
        const std::array<std::uint32_t, 1> sources{surface};
        rebuild_->density = std::make_unique<PhotonDensity>(map, sources, PhotonSelection::Full);
        rebuild_->texels = registry_.world_texels(surface);
        // Photons that change from now on need another rebuild; this one sees the tree's snapshot.
        deltas_.consume_full(map, surface);
    }
    RebuildState& rebuild = *rebuild_;
    RadiancePage& page = registry_.aim_page(page_id);
    const double metres_per_texel = mapped.world_metres_per_texel;
    DensitySettings density = settings_.density;
    if (metres_per_texel > 0.0 && settings_.max_radius_texels > 0.0f) {
        density.max_radius =
            static_cast<float>(static_cast<double>(settings_.max_radius_texels) * metres_per_texel);
    }
    const std::size_t first = rebuild.cursor;
    const std::size_t end = std::min(rebuild.texels.size(), first + max_texels);
    int x0 = page.size;
    int y0 = page.size;
    int x1 = -1;
    int y1 = -1;
    const float ray_length = static_cast<float>(settings_.enclosure_ray_texels * metres_per_texel);
    for (std::size_t i = first; i < end; ++i) {
        const SurfaceTexel& texel = mapped.texels.texels[i];
        glm::vec3 radiance(0.0f);
        if (ray_length > 0.0f && enclosed(rebuild.texels[i], ray_length)) {
            page.at(texel.x, texel.y) = radiance;
            ++enclosed_texels_;
            x0 = std::min(x0, texel.x);
            y0 = std::min(y0, texel.y);
            x1 = std::max(x1, texel.x);
            y1 = std::max(y1, texel.y);
            continue;
        }
        const DensitySample found =
            rebuild.density->sample(rebuild.texels[i].position, rebuild.texels[i].normal, density);
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
    rebuild.cursor = end;
    const bool complete = rebuild.cursor >= rebuild.texels.size();
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
        page.mark_changed({x0, y0, x1 - x0 + 1, y1 - y0 + 1});
    }
    texels_ += end - first;
    if (complete) {
        if (built_.size() <= surface) {
            built_.resize(surface + 1, false);
        }
        built_[surface] = true;
        ++rebuilds_;
        rebuild_.reset();
    }
    return end - first;
}

bool AimRebuilder::enclosed(const GatherTexel& texel, float ray_length) const {
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
        free += scene.occluded(origin, direction, ray_length) ? 0 : 1;
    }
    return free <= kFreeAllowed;
}

void AimRebuilder::dilate(std::uint32_t surface, RadiancePage& page) const {
    const MapSurface& mapped = registry_.surface(surface);
    const std::int32_t page_id = registry_.page_of(surface);
    const int size = page.size;
    const auto owner = [&](int x, int y) { return registry_.owner(page_id, x, y); };
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

bool AimRebuilder::ready() const {
    // A gather pass started before every lit surface has an AIM would gather black where the AIM is
    // missing and consume the delta_i that should have brought it back.
    const PhotonMap& map = world_.photon_map();
    const std::span<const MapSurface> surfaces = registry_.surfaces();
    for (std::uint32_t s = 0; s < surfaces.size() && s < map.surface_count(); ++s) {
        if (!built(s) && !surfaces[s].texels.texels.empty() &&
            map.surface(s).stored_energy.value() > 0.0) {
            return false;
        }
    }
    return true;
}

}  // namespace luxel::lighting
