#include "luxel/lighting/core/illumination_maps.hpp"

#include <utility>

#include "aim_rebuilder.hpp"
#include "iim_gather_passes.hpp"
#include "map_registry.hpp"

// The maps' public face: each call goes to the stage that owns it.
namespace luxel::lighting {

IlluminationMaps::IlluminationMaps(ecs::Registry& registry, const PhotonWorld& world,
                                   IlluminationSettings settings)
    : settings_(settings),
      registry_(std::make_unique<MapRegistry>(registry, world)),
      aims_(std::make_unique<AimRebuilder>(*registry_, world, deltas_, settings_)),
      gathers_(std::make_unique<IimGatherPasses>(*registry_, *aims_, world, deltas_, settings_)) {
    sync();
}

IlluminationMaps::~IlluminationMaps() = default;

void IlluminationMaps::sync() {
    registry_->sync();
    aims_->sync();
    gathers_->sync();
}

std::vector<MapRequest> IlluminationMaps::aim_requests() const {
    return aims_->requests();
}

std::size_t IlluminationMaps::rebuild_aim(std::uint32_t surface, std::size_t max_texels,
                                          JobSystem* jobs) {
    return aims_->rebuild(surface, max_texels, jobs);
}

std::optional<std::uint32_t> IlluminationMaps::next_aim_surface() const {
    return aims_->next_surface();
}

std::vector<MapRequest> IlluminationMaps::gather_requests() const {
    return gathers_->requests();
}

std::size_t IlluminationMaps::gather(std::uint32_t surface, std::size_t max_texels,
                                     IrradianceGatherer& gatherer, double now_seconds) {
    return gathers_->gather(surface, max_texels, gatherer, now_seconds);
}

std::optional<std::uint32_t> IlluminationMaps::next_gather_surface() const {
    return gathers_->next_surface();
}

bool IlluminationMaps::aims_ready() const {
    return aims_->ready();
}

double IlluminationMaps::refined_share() const {
    return gathers_->refined_share();
}

bool IlluminationMaps::aims_current() const {
    return aims_->current();
}

void IlluminationMaps::set_refinement(bool refine) {
    gathers_->set_refinement(refine);
}

void IlluminationMaps::set_view(std::optional<ViewHint> view) {
    gathers_->set_view(view);
}

const RadianceAtlas& IlluminationMaps::aim() const {
    return registry_->aim();
}

std::span<const IimPage> IlluminationMaps::iim_pages() const {
    return std::as_const(*registry_).iim_pages();
}

std::span<IimPage> IlluminationMaps::iim_pages() {
    return registry_->iim_pages();
}

std::span<const MapSurface> IlluminationMaps::surfaces() const {
    return registry_->surfaces();
}

const GatherPassState& IlluminationMaps::gather_state(std::uint32_t s) const {
    return gathers_->state(s);
}

const RefinementStats& IlluminationMaps::refinement(std::uint32_t s) const {
    return gathers_->refinement(s);
}

MapCounters IlluminationMaps::counters() const {
    MapCounters counters;
    counters.aim_rebuilds = aims_->rebuilds();
    counters.aim_texels = aims_->texels();
    counters.enclosed_texels = aims_->enclosed_texels();
    counters.edge_texels = aims_->contacts().edges_found();
    counters.gather_passes = gathers_->passes();
    counters.texels_kept = gathers_->texels_kept();
    counters.texels_gathered = gathers_->texels_gathered();
    counters.seam_stitches = gathers_->seams().stitches();
    counters.seam_texels = gathers_->seams().texels();
    return counters;
}

std::vector<SeamSample> IlluminationMaps::seam_samples() const {
    std::vector<SeamSample> all;
    for (const std::vector<SeamSample>& object : registry_->seams()) {
        all.insert(all.end(), object.begin(), object.end());
    }
    return all;
}

std::uint64_t IlluminationMaps::emission_version() const {
    return registry_->emission_version();
}

std::vector<GatherTexel> IlluminationMaps::world_texels(std::uint32_t surface) const {
    return registry_->world_texels(surface);
}

}  // namespace luxel::lighting
