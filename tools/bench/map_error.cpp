#include "map_error.hpp"

#include <fstream>
#include <map>
#include <tuple>

#include <glm/gtc/constants.hpp>
#include <nlohmann/json.hpp>

#include "luxel/lighting/reference/error_metrics.hpp"
#include "luxel/lighting/reference/local_error.hpp"
#include "luxel/runtime/error.hpp"

namespace luxel::bench {
namespace {

using lighting::reference::ReferenceScene;

/// The reference's texel under a caustic photon, from the light-map UV the photon keeps; -1
/// where the reference bins none (ReferenceScene::open_texel_at).
std::int64_t texel_of(const lighting::CausticPhoton& photon, const ReferenceScene& scene) {
    return scene.open_texel_at(photon.surface, photon.lightmap_uv());
}

}  // namespace

RealTimeMaps read_real_time(const lighting::LightingSystem& lighting, const ReferenceScene& scene,
                            double now_seconds) {
    const lighting::IlluminationMaps& maps = lighting.maps();
    RealTimeMaps out;
    out.indirect.assign(scene.texel_count(), glm::dvec3(0.0));
    out.caustic.assign(scene.texel_count(), glm::dvec3(0.0));
    out.aim.assign(scene.texel_count(), glm::dvec3(0.0));
    for (const auto& surface : scene.surfaces()) {
        const lighting::MapSurface& map = maps.surfaces()[surface.surface];
        const std::int32_t page = maps.aim().surface_page[surface.surface];
        if (page < 0) {
            continue;
        }
        const lighting::IimPage& iim = maps.iim_pages()[static_cast<std::size_t>(page)];
        const lighting::RadiancePage& aim = maps.aim().pages[static_cast<std::size_t>(page)];
        glm::dvec3 to_irradiance(0.0);
        for (int c = 0; c < 3; ++c) {
            const double albedo = map.albedo[c];
            to_irradiance[c] = albedo > 0.0 ? glm::pi<double>() / albedo : 0.0;
        }
        const glm::dvec3 scale =
            map.content == lighting::IimContent::Radiance ? to_irradiance : glm::dvec3(1.0);
        for (std::size_t i = 0; i < surface.texels.size(); ++i) {
            const auto& texel = surface.texels[i];
            const glm::vec3 shown = iim.shown(texel.x, texel.y, now_seconds);
            out.indirect[surface.first_texel + i] = glm::dvec3(shown) * scale;
            out.aim[surface.first_texel + i] = glm::dvec3(aim.at(texel.x, texel.y)) * to_irradiance;
        }
    }
    for (const lighting::CausticPair& pair : lighting.photons().caustics()) {
        for (std::uint32_t k = 0; k < pair.photons.slice_count(); ++k) {
            for (const lighting::CausticPhoton& photon : pair.photons.slice(k)) {
                ++out.caustic_photons;
                const std::int64_t t = photon.surface >= 0 ? texel_of(photon, scene) : -1;
                const double area = t >= 0 ? scene.texel(static_cast<std::size_t>(t)).area : 0.0;
                if (!(area > 0.0)) {
                    ++out.caustic_unbinned;
                    continue;
                }
                out.caustic[static_cast<std::size_t>(t)] += glm::dvec3(photon.power) / area;
            }
        }
    }
    return out;
}

std::vector<std::uint32_t> texel_regions(const ReferenceScene& scene) {
    std::vector<std::uint32_t> regions(scene.texel_count(), 0);
    std::map<std::tuple<std::uint32_t, int, int>, std::uint32_t> ids;
    for (const auto& surface : scene.surfaces()) {
        for (std::size_t i = 0; i < surface.texels.size(); ++i) {
            const auto& texel = surface.texels[i];
            const auto key =
                std::make_tuple(surface.surface, texel.x / kRegionTexels, texel.y / kRegionTexels);
            const auto id = ids.try_emplace(key, static_cast<std::uint32_t>(ids.size())).first;
            regions[surface.first_texel + i] = id->second;
        }
    }
    return regions;
}

MapErrors map_errors(const RealTimeMaps& maps, const ReferenceMaps& reference,
                     const std::vector<std::uint32_t>& regions) {
    if (maps.indirect.size() != reference.area.size()) {
        throw Error("luxel-bench: the light maps have " + std::to_string(maps.indirect.size()) +
                    " texels, the reference " + std::to_string(reference.area.size()));
    }
    MapErrors errors;
    errors.indirect =
        lighting::reference::relative_rmse(maps.indirect, reference.indirect(), reference.area);
    errors.caustic =
        lighting::reference::relative_rmse(maps.caustic, reference.caustic(), reference.area);
    const lighting::reference::LocalError local = lighting::reference::local_error(
        maps.indirect, reference.indirect(), reference.area, regions);
    errors.indirect_region = local.worst_region;
    errors.indirect_p99 = local.texel_p99;
    return errors;
}

void write_maps_json(const std::filesystem::path& path, const ReferenceScene& scene,
                     const RealTimeMaps& maps, const ReferenceMaps& reference) {
    const auto rgb = [](const glm::dvec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); };
    nlohmann::json texels = nlohmann::json::array();
    for (const auto& surface : scene.surfaces()) {
        for (std::size_t i = 0; i < surface.texels.size(); ++i) {
            const std::size_t t = surface.first_texel + i;
            texels.push_back({{"surface", surface.surface},
                              {"x", surface.texels[i].x},
                              {"y", surface.texels[i].y},
                              {"area", reference.area[t]},
                              {"indirect", rgb(maps.indirect[t])},
                              {"ref_indirect", rgb(reference.indirect()[t])},
                              {"caustic", rgb(maps.caustic[t])},
                              {"ref_caustic", rgb(reference.caustic()[t])},
                              {"ref_direct", rgb(reference.value[0][t])},
                              {"aim", rgb(maps.aim[t])}});
        }
    }
    std::filesystem::create_directories(path.parent_path());
    std::ofstream out(path);
    out << nlohmann::json{{"texels", texels}}.dump() << "\n";
    if (!out) {
        throw Error("cannot write " + path.string());
    }
}

}  // namespace luxel::bench
