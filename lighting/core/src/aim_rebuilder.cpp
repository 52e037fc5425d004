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

namespace {

/// Whether the texel's centre lies on its surface (not a border texel placed at the nearest
/// point of the surface): such centres sample the surface uniformly.
bool on_surface_centre(const SurfaceTexel& texel) {
    constexpr float kTolerance = 1e-3f;  // page texels; the point is interpolated in floats
    const glm::vec2 centre(static_cast<float>(texel.x) + 0.5f, static_cast<float>(texel.y) + 0.5f);
    return std::abs(texel.page_point.x - centre.x) <= kTolerance &&
           std::abs(texel.page_point.y - centre.y) <= kTolerance;
}

}  // namespace

/// A rebuild in progress: the surface's kd-tree (the only one in memory) and where it got to.
struct AimRebuilder::RebuildState {
    std::uint32_t surface = 0;
    std::unique_ptr<PhotonDensity> density;
    std::vector<GatherTexel> texels;  ///< world space, at the rebuild's start
    /// A local rebuild's texel indices (texels[k] is texel subset[k]); empty for a full one.
    std::vector<std::uint32_t> subset;
    std::uint64_t first_serial = 0;  ///< a local rebuild's LocalMarks::first_serial
    std::size_t cursor = 0;
    /// A full rebuild's power bookkeeping (keep_power): the tree's photons' power, and the
    /// estimates (irradiance, channels summed, before any scale) at the texels whose centre
    /// lies on the surface, which sample it uniformly (conformal charts, one scale).
    double photon_power = 0.0;
    double interior_irradiance = 0.0;
    std::size_t interior_texels = 0;
    [[nodiscard]] bool local() const { return !subset.empty(); }
    [[nodiscard]] std::uint32_t index(std::size_t k) const {
        return local() ? subset[k] : static_cast<std::uint32_t>(k);
    }
};

AimRebuilder::AimRebuilder(MapRegistry& registry, const PhotonWorld& world, SurfaceDeltas& deltas,
                           const IlluminationSettings& settings)
    : registry_(registry), world_(world), deltas_(deltas), settings_(settings) {}

AimRebuilder::~AimRebuilder() = default;

void AimRebuilder::sync() {
    ++syncs_;
    marked_in_last_sync_ = false;
    if (!awaited_groups_.empty()) {
        // Retraced since: no longer pending (one queued again by a probe stays awaited).
        std::vector<std::uint32_t> pending = world_.pending_groups();
        std::sort(pending.begin(), pending.end());
        std::erase_if(awaited_groups_, [&](std::uint32_t group) {
            return !std::binary_search(pending.begin(), pending.end(), group);
        });
    }
    if (!settings_.local_passes) {
        return;  // the paper's method: an AIM follows its photons only
    }
    bool& marked = marked_in_last_sync_;
    for (const MapRegistry::NearbyChange& change : registry_.nearby_changes()) {
        // An AIM not built yet is built whole, from the geometry as it is then. The moved
        // object's own AIM moves with it (looked up by its light-map UVs) until its photons,
        // every one of which the move changes, ask for a full rebuild: a local one before they
        // are retraced would estimate from hits where the object no longer is.
        if (built(change.surface) && registry_.page_of(change.surface) >= 0 &&
            !registry_.moved_in_last_sync(change.surface)) {
            if (!marked) {
                ++change_serial_;
                marked = true;
                // The groups queued by now include those exact invalidation found crossing
                // the change: the local rebuilds wait for their photons.
                const std::vector<std::uint32_t>& pending = world_.pending_groups();
                awaited_groups_.insert(awaited_groups_.end(), pending.begin(), pending.end());
                std::sort(awaited_groups_.begin(), awaited_groups_.end());
                awaited_groups_.erase(std::unique(awaited_groups_.begin(), awaited_groups_.end()),
                                      awaited_groups_.end());
            }
            mark(change.surface, change.texels);
        }
    }
}

void AimRebuilder::mark(std::uint32_t s, std::span<const std::uint32_t> texels) {
    if (marks_.size() <= s) {
        marks_.resize(s + 1);
    }
    LocalMarks& marks = marks_[s];
    marks.marked.resize(registry_.surface(s).texels.texels.size(), 0);
    const bool had_marks = !marks.texels.empty();
    for (const std::uint32_t i : texels) {
        if (i < marks.marked.size() && marks.marked[i] == 0) {
            marks.marked[i] = 1;
            marks.texels.push_back(i);
        }
    }
    if (!had_marks && !marks.texels.empty()) {
        marks.first_serial = change_serial_;
        marks.first_sync = syncs_;
    }
}

std::uint64_t AimRebuilder::local_current_through() const {
    std::uint64_t through = change_serial_;
    for (std::uint32_t s = 0; s < marks_.size(); ++s) {
        // A surface gone (or never given photons) keeps its marks but is never rebuilt; marks
        // not due yet (waiting for retraces) hold it back like any other.
        if (has_marks(s) && registry_.live(s) && s < world_.photon_map().surface_count()) {
            through = std::min(through, marks_[s].first_serial - 1);
        }
    }
    if (rebuild_ && rebuild_->local()) {
        through = std::min(through, rebuild_->first_serial - 1);
    }
    return through;
}

bool AimRebuilder::needs_full_rebuild(std::uint32_t s) const {
    const PhotonMap& map = world_.photon_map();
    if (!registry_.live(s) || s >= map.surface_count()) {
        return false;
    }
    const SurfacePhotons& photons = map.surface(s);
    const double change = relative(deltas_.full(map, s), photons.stored_energy.value());
    const bool in_progress = (rebuild_ && rebuild_->surface == s && !rebuild_->local()) ||
                             (paused_ && paused_->surface == s);
    return !built(s) || in_progress || change > settings_.aim_threshold;
}

bool AimRebuilder::needs_rebuild(std::uint32_t s) const {
    if (needs_full_rebuild(s)) {
        return true;
    }
    const bool in_progress = rebuild_ && rebuild_->surface == s;
    return registry_.live(s) && s < world_.photon_map().surface_count() &&
           (in_progress || marks_due(s));
}

bool AimRebuilder::marks_due(std::uint32_t s) const {
    // The groups whose paths crossed the change are retraced first (exact invalidation queues
    // them in the frame of the change): a density estimate from the photons before them would
    // keep the floor beside a crate's new place lit. Where those groups keep being queued
    // again (objects that move every frame), the marks go anyway after kMaxRetraceWait frames.
    constexpr std::uint64_t kMaxRetraceWait = 8;
    return has_marks(s) &&
           (awaited_groups_.empty() || syncs_ - marks_[s].first_sync >= kMaxRetraceWait);
}

bool AimRebuilder::current() const {
    // Local rebuilds do not count: near an object that moves every frame they never run out,
    // and refinement, which waits for current AIMs, would stop everywhere in the level. The
    // texels of the local gather passes near them are gathered again after them instead
    // (local_current_through).
    for (std::uint32_t s = 0; s < registry_.surfaces().size(); ++s) {
        if (needs_full_rebuild(s)) {
            return false;
        }
    }
    return true;
}

double AimRebuilder::priority(std::uint32_t s) const {
    const MapSurface& mapped = registry_.surface(s);
    // A local rebuild in progress, then the texels marked next to a change (a few texels, which
    // the local gather passes there wait for), then a full rebuild in progress (or paused),
    // then unbuilt maps, then the surfaces whose light changed most per square metre.
    constexpr double kTop = std::numeric_limits<double>::max();
    const bool in_progress = rebuild_ && rebuild_->surface == s;
    if (in_progress && rebuild_->local()) {
        return kTop;
    }
    if (marks_due(s) && built(s)) {
        // After a local rebuild, a full one (in progress or asked for) goes first: near
        // objects that move every frame marks never run out, and full rebuilds must not wait
        // for them forever.
        return full_turn_ ? -1.0 : kTop / 2.0;
    }
    if (in_progress || (paused_ && paused_->surface == s)) {
        return kTop / 4.0;
    }
    if (!built(s)) {
        return kTop / 8.0;
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

std::size_t AimRebuilder::rebuild(std::uint32_t surface, std::size_t max_texels, JobSystem* jobs) {
    const MapSurface& mapped = registry_.surface(surface);
    const std::int32_t page_id = registry_.page_of(surface);
    const PhotonMap& map = world_.photon_map();
    if (page_id < 0 || surface >= map.surface_count() || max_texels == 0) {
        return 0;
    }
    if (rebuild_ && rebuild_->surface != surface && !rebuild_->local() && !paused_ &&
        marks_due(surface) && built(surface)) {
        // A local rebuild does not wait for a full one (a floor's thousands of texels, tens of
        // frames at a small budget): the full one pauses, its tree kept, and goes on after.
        paused_ = std::move(rebuild_);
    }
    if (rebuild_ && rebuild_->surface != surface) {
        // Otherwise one tree at a time: the rebuild in progress goes on (this call's effort
        // goes to it), so rebuilds finish in order however the requests interleave. Only a
        // rebuild whose surface went away is dropped.
        if (registry_.live(rebuild_->surface)) {
            return rebuild(rebuild_->surface, max_texels, jobs);
        }
        rebuild_.reset();
        if (paused_ && registry_.live(paused_->surface)) {
            rebuild_ = std::move(paused_);
            return rebuild(rebuild_->surface, max_texels, jobs);
        }
        paused_.reset();
    }
    if (!rebuild_) {
        start(surface);
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
    // Indices run over rebuild.texels (the subset's, for a local rebuild); `texel` is the
    // surface's own.
    int x0 = page.size;
    int y0 = page.size;
    int x1 = -1;
    int y1 = -1;
    const float ray_length = static_cast<float>(settings_.enclosure_ray_texels * metres_per_texel);
    // Each texel's estimate reads the tree and the ray scene and writes its own page texel, so
    // the slice's texels are placed in parallel when a JobSystem is given (the warm-up's AIM
    // rebuilds, serial, were a twentieth of it beside the parallel gathers).
    std::vector<std::uint8_t> enclosed_here(end - first, 0);
    // The irradiance at a point of the surface near texel `index` (its centre, or an edge
    // texel's open point), unscaled, and the reflected radiance the page holds for it.
    const auto estimate = [&](const glm::vec3& position, const glm::vec3& normal,
                              std::uint32_t index) {
        glm::dvec3 irradiance(0.0);
        const DensitySample found = rebuild.density->sample(position, normal, density);
        if (found.radius > 0.0 && metres_per_texel > 0.0) {
            const double on_surface = mapped.footprint.fraction(
                index, found.radius / metres_per_texel, settings_.density.kernel);
            const double area = glm::pi<double>() * found.radius * found.radius * on_surface;
            if (area > 0.0) {
                irradiance = found.power / area;
            }
        }
        return irradiance;
    };
    const double scale = power_scale(surface) / glm::pi<double>();
    const auto radiance = [&](const glm::dvec3& irradiance) {
        return sanitized(glm::vec3(glm::dvec3(mapped.albedo) * irradiance * scale));
    };
    std::vector<double> interior_here(end - first, -1.0);
    const auto place = [&](std::size_t k) {
        const std::size_t i = first + k;
        const SurfaceTexel& texel = mapped.texels.texels[rebuild.index(i)];
        if (ray_length > 0.0f && enclosed(rebuild.texels[i], ray_length)) {
            page.at(texel.x, texel.y) = glm::vec3(0.0f);
            enclosed_here[k] = 1;
            interior_here[k] = on_surface_centre(texel) ? 0.0 : -1.0;
            return;
        }
        const glm::dvec3 irradiance =
            estimate(rebuild.texels[i].position, rebuild.texels[i].normal, rebuild.index(i));
        page.at(texel.x, texel.y) = radiance(irradiance);
        if (on_surface_centre(texel)) {
            const double sum = irradiance.x + irradiance.y + irradiance.z;
            interior_here[k] = std::isfinite(sum) ? sum : 0.0;
        }
    };
    if (jobs != nullptr && end - first > 1) {
        jobs->parallel_for(0, end - first, place);
    } else {
        for (std::size_t k = 0; k < end - first; ++k) {
            place(k);
        }
    }
    std::vector<std::uint32_t> placed(end - first);
    for (std::size_t i = first; i < end; ++i) {
        const SurfaceTexel& texel = mapped.texels.texels[rebuild.index(i)];
        enclosed_texels_ += enclosed_here[i - first];
        if (interior_here[i - first] >= 0.0) {
            rebuild.interior_irradiance += interior_here[i - first];
            ++rebuild.interior_texels;
        }
        placed[i - first] = rebuild.index(i);
        x0 = std::min(x0, texel.x);
        y0 = std::min(y0, texel.y);
        x1 = std::max(x1, texel.x);
        y1 = std::max(y1, texel.y);
    }
    if (settings_.contact_texels) {
        contacts_.record(surface, mapped.texels.texels.size(), placed, enclosed_here);
    }
    rebuild.cursor = end;
    const bool complete = rebuild.cursor >= rebuild.texels.size();
    if (complete) {
        if (settings_.contact_texels) {
            find_edges(rebuild, ray_length, jobs);
            // An edge texel's AIM is the light at its open point, as its gather is: a gather ray
            // that meets the floor right beside an object reads it bilinearly.
            const std::span<const TexelCover> cover = contacts_.cover(surface);
            const std::span<const glm::vec3> points = contacts_.gather_points(surface);
            for (std::size_t i = 0; i < rebuild.texels.size(); ++i) {
                const std::uint32_t index = rebuild.index(i);
                if (index < cover.size() && cover[index] == TexelCover::Edge) {
                    const SurfaceTexel& texel = mapped.texels.texels[index];
                    const glm::vec3 point(mapped.to_world * glm::vec4(points[index], 1.0f));
                    page.at(texel.x, texel.y) =
                        radiance(estimate(point, rebuild.texels[i].normal, index));
                }
            }
        }
        if (settings_.aim_keeps_power && !rebuild.local()) {
            keep_power(rebuild, page);
        }
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
        if (rebuild.local()) {
            full_turn_ = true;
        } else {
            if (built_.size() <= surface) {
                built_.resize(surface + 1, false);
            }
            built_[surface] = true;
            ++rebuilds_;
        }
        rebuild_ = std::move(paused_);  // a full rebuild a local one paused goes on
    }
    return end - first;
}

void AimRebuilder::start(std::uint32_t surface) {
    const PhotonMap& map = world_.photon_map();
    // Marks make a local rebuild even where delta_f asks for a full one, which stays asked for:
    // the texels next to the change first, in a frame or two, then the rest.
    const bool full = !built(surface) || !marks_due(surface);
    rebuild_ = std::make_unique<RebuildState>();
    rebuild_->surface = surface;
    const std::array<std::uint32_t, 1> sources{surface};
    rebuild_->density = std::make_unique<PhotonDensity>(map, sources, PhotonSelection::Full);
    // Either way the texels are placed where the geometry is now: the marks are taken. (Keeping
    // marks still waiting for their retraces through a full rebuild, for a local one after it,
    // was tried: crate-footprint's worst region came back at 13-24 frames at 4 ms instead of
    // 11-12.)
    LocalMarks marks;
    if (surface < marks_.size()) {
        std::swap(marks, marks_[surface]);
    }
    if (full) {
        full_turn_ = false;
        rebuild_->texels = registry_.world_texels(surface);
        glm::dvec3 power(0.0);
        for (std::size_t i = 0; i < map.surface(surface).hit_count(); ++i) {
            power += glm::dvec3(map.hit(surface, i).power);
        }
        rebuild_->photon_power = power.x + power.y + power.z;
        // Photons that change from now on need another rebuild; this one sees the tree's
        // snapshot.
        deltas_.consume_full(map, surface);
        return;
    }
    // A local rebuild: only the marked texels, and delta_f stays for a full rebuild to consume
    // (the photons' change elsewhere on the surface is not looked at).
    std::sort(marks.texels.begin(), marks.texels.end());
    rebuild_->subset = std::move(marks.texels);
    rebuild_->first_serial = marks.first_serial;
    rebuild_->texels = registry_.world_texels(surface, rebuild_->subset);
}

void AimRebuilder::keep_power(const RebuildState& rebuild, RadiancePage& page) {
    const MapSurface& mapped = registry_.surface(rebuild.surface);
    // The surface's world area: the object-space area times the transform's scale squared
    // (world over object metres per texel).
    const double object_metres = mapped.texels.metres_per_texel;
    const double world_area =
        object_metres > 0.0 ? mapped.texels.area * (mapped.world_metres_per_texel / object_metres) *
                                  (mapped.world_metres_per_texel / object_metres)
                            : 0.0;
    const double integral = rebuild.interior_texels > 0
                                ? world_area * rebuild.interior_irradiance /
                                      static_cast<double>(rebuild.interior_texels)
                                : 0.0;
    // Too few texels to sample the surface, or too few photons to say anything: the estimate
    // as it is. The scale is bounded: the nearest-N bias is a few per cent (RESULTS.md), so a
    // larger mismatch means the texels do not see where the photons are (a surface the light
    // map covers in part), which no scale mends.
    constexpr std::size_t kFewestTexels = 16;
    constexpr double kLargest = 1.25;
    double wanted = 1.0;
    if (rebuild.interior_texels >= kFewestTexels && integral > 0.0 && rebuild.photon_power > 0.0 &&
        std::isfinite(integral) && std::isfinite(rebuild.photon_power)) {
        wanted = std::clamp(rebuild.photon_power / integral, 1.0 / kLargest, kLargest);
    }
    if (power_scales_.size() <= rebuild.surface) {
        power_scales_.resize(rebuild.surface + 1, 1.0);
    }
    // The texels were placed with the old scale (this rebuild's slices and any local rebuild
    // since); all of them take the new one.
    const double old_scale = power_scales_[rebuild.surface];
    power_scales_[rebuild.surface] = wanted;
    const float change = static_cast<float>(wanted / old_scale);
    if (change == 1.0f) {
        return;
    }
    for (const SurfaceTexel& texel : mapped.texels.texels) {
        page.at(texel.x, texel.y) *= change;
    }
}

void AimRebuilder::find_edges(const RebuildState& rebuild, float ray_length, JobSystem* jobs) {
    if (!(ray_length > 0.0f)) {
        return;  // no enclosure rays, nothing enclosed
    }
    const MapSurface& mapped = registry_.surface(rebuild.surface);
    std::vector<std::uint32_t> indices(rebuild.texels.size());
    for (std::size_t i = 0; i < indices.size(); ++i) {
        indices[i] = rebuild.index(i);
    }
    contacts_.find_edges(
        rebuild.surface, mapped, indices, rebuild.texels,
        [&](const glm::vec3& position, const glm::vec3& normal) {
            GatherTexel probe;
            probe.position = position;
            probe.normal = normal;
            return enclosed(probe, ray_length);
        },
        jobs);
}

bool AimRebuilder::enclosed(const GatherTexel& texel, float ray_length) const {
    // Rays over the hemisphere: the normal and eight cosine-distributed directions around it.
    // A texel under an object resting on its surface has (nearly) all of them blocked within a
    // texel or two; one in a corner or beside a wall has the ones pointing away free (half or
    // more). Two free rays are allowed: where a box rests on a bumpy floor, grazing rays slip
    // out through the gaps between the bumps although hardly any light gets in.
    //
    // A texel inside a closed object is enclosed however far its walls are: a crate modelled
    // with a bottom face, resting on the floor, has that face in the floor's plane, so the
    // rays start inside the crate and meet its walls from behind, a quarter metre away. The ray
    // along the normal tells (its first hit faces away from it); then every probe that meets a
    // face from behind, at any distance, counts as blocked. A texel under a table top, which
    // the normal ray also meets from behind, still has its sideways probes free.
    constexpr int kProbes = 9;
    constexpr int kFreeAllowed = 2;
    const RayScene& scene = world_.ray_scene();
    const glm::vec3 origin = offset_ray_origin(texel.position, texel.normal);
    // Glass and water enclose nothing: light passes through them (the floor of a pool, under
    // its water sheet, sees that sheet from behind at every angle and is lit all the same).
    const std::vector<TraceMaterial>& materials = world_.materials();
    const auto from_behind = [&](const glm::vec3& direction, const std::optional<RayHit>& hit) {
        return hit && glm::dot(direction, hit->geometric_normal) > 0.0f &&
               !(hit->material < materials.size() &&
                 materials[hit->material].scattering == Scattering::Dielectric);
    };
    const std::optional<RayHit> along_normal = scene.intersect(origin, texel.normal);
    const bool inside = from_behind(texel.normal, along_normal);
    int free = 0;
    for (int k = 0; k < kProbes && free <= kFreeAllowed; ++k) {
        const glm::vec3 direction =
            k == 0 ? texel.normal
                   : cosine_direction(
                         texel.normal,
                         glm::dvec2((static_cast<double>(k) - 0.5) / (kProbes - 1),
                                    std::fmod(static_cast<double>(k) * 0.6180339887498949, 1.0)));
        bool blocked = false;
        if (k == 0) {
            blocked = inside || (along_normal && along_normal->distance < ray_length);
        } else if (inside) {
            const std::optional<RayHit> hit = scene.intersect(origin, direction);
            blocked = from_behind(direction, hit) || (hit && hit->distance < ray_length);
        } else {
            blocked = scene.occluded(origin, direction, ray_length);
        }
        free += blocked ? 0 : 1;
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
