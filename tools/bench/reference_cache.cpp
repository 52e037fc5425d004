#include "reference_cache.hpp"

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "luxel/lighting/reference/reference_integrator.hpp"
#include "luxel/runtime/clock.hpp"
#include "luxel/runtime/error.hpp"

namespace luxel::bench {
namespace {

using namespace lighting::reference;

constexpr std::uint32_t kPasses = 4;
constexpr std::array<const char*, 3> kNames{"direct", "indirect", "caustic"};

std::uint64_t share(std::uint64_t total, std::uint32_t pass) {
    return total / kPasses + (pass < total % kPasses ? 1 : 0);
}

bool load(const std::filesystem::path& file, ReferenceMaps& maps, std::size_t texels) {
    std::ifstream in(file);
    if (!in) {
        return false;
    }
    try {
        const nlohmann::json json = nlohmann::json::parse(in);
        if (json.at("key").get<std::string>() != maps.key) {
            return false;  // a hash collision, or an older format
        }
        maps.area = json.at("area").get<std::vector<double>>();
        maps.seconds = json.at("seconds").get<double>();
        for (std::size_t c = 0; c < 3; ++c) {
            const auto flat = json.at(kNames[c]).get<std::vector<double>>();
            if (flat.size() != 3 * texels) {
                return false;
            }
            maps.value[c].resize(texels);
            for (std::size_t t = 0; t < texels; ++t) {
                maps.value[c][t] = {flat[3 * t], flat[3 * t + 1], flat[3 * t + 2]};
            }
            maps.relative_standard_error[c] =
                json.at("relative_standard_error").at(kNames[c]).get<double>();
        }
        return maps.area.size() == texels;
    } catch (const nlohmann::json::exception&) {
        return false;  // unreadable: computed again and overwritten
    }
}

void save(const std::filesystem::path& file, const ReferenceMaps& maps) {
    nlohmann::json json;
    json["key"] = maps.key;
    json["seconds"] = maps.seconds;
    json["area"] = maps.area;
    for (std::size_t c = 0; c < 3; ++c) {
        std::vector<double> flat;
        flat.reserve(3 * maps.value[c].size());
        for (const glm::dvec3& v : maps.value[c]) {
            flat.insert(flat.end(), {v.x, v.y, v.z});
        }
        json[kNames[c]] = flat;
        json["relative_standard_error"][kNames[c]] = maps.relative_standard_error[c];
    }
    std::filesystem::create_directories(file.parent_path());
    // Written beside and renamed: a run killed mid-write leaves no truncated entry.
    const std::filesystem::path partial = file.string() + ".partial";
    {
        std::ofstream out(partial);
        out << json.dump();
        if (!out) {
            throw Error("cannot write " + partial.string());
        }
    }
    std::filesystem::rename(partial, file);
}

}  // namespace

std::string cache_hash(const std::string& key) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (const char c : key) {
        h ^= static_cast<std::uint8_t>(c);
        h *= 0x100000001b3ull;
    }
    char buffer[17];
    std::snprintf(buffer, sizeof(buffer), "%016" PRIx64, h);
    return buffer;
}

lighting::reference::ReferenceSettings reference_settings(const ReferenceSpec& spec) {
    using namespace lighting::reference;
    ReferenceSettings settings;
    settings.seed = spec.seed;
    settings.caustics.seed = spec.seed;
    settings.indirect = IndirectMethod::Photons;
    settings.indirect_photons.seed = spec.seed;
    // The light maps are compared with what the IIM should hold, which includes the direct
    // light of area lights and skies (the renderer adds only delta lights' direct light).
    settings.paths.gathered_as_indirect = true;
    return settings;
}

ReferenceMaps reference_for(const std::filesystem::path& cache_dir, const std::string& pose,
                            const ReferenceScene& scene, const ReferenceSpec& spec,
                            JobSystem& jobs) {
    ReferenceMaps maps;
    // The version names the reference's algorithms: v2, caustic photons from its own
    // CausticDiscEmitter instead of the real-time CausticEmitter; v3, texel areas counting only
    // the part no object rests on (ReferenceTexel::area); v4, glass and water enclose nothing (a
    // pool's floor under its water sheet is open); v5, a closed solid's volume absorbs on the
    // way to a diffuse surface inside it too (ClosedMedium).
    maps.key = pose + ";indirect_photons=" + std::to_string(spec.indirect_photons) +
               ";caustic_photons=" + std::to_string(spec.caustic_photons) +
               ";spp=" + std::to_string(spec.spp) + ";seed=" + std::to_string(spec.seed) +
               ";texels=" + std::to_string(scene.texel_count()) + ";reference=v5";
    // Area lights' and skies' direct light counts as indirect (reference_settings): a level
    // that has them gets a new entry; one lit by delta lights alone keeps its reference.
    const auto lights = scene.lights();
    if (std::any_of(
            lights.begin(), lights.end(),
            [](const lighting::reference::ReferenceLight& light) { return !light.is_delta(); })) {
        maps.key += ";gathered=indirect";
    }
    // Paths past a texel read base-colour textures per hit (HitTextures): the same for a
    // textured level.
    if (scene.textured()) {
        maps.key += ";textures=per-hit";
    }
    maps.hash = cache_hash(maps.key);
    const std::filesystem::path file = cache_dir / (maps.hash + ".json");
    if (load(file, maps, scene.texel_count())) {
        maps.from_cache = true;
        std::fprintf(stderr,
                     "luxel-bench: reference %s from cache (computed in %.1f s; rel. std. error "
                     "indirect %.4f, caustic %.4f)\n",
                     maps.hash.c_str(), maps.seconds, maps.relative_standard_error[1],
                     maps.relative_standard_error[2]);
        return maps;
    }
    std::fprintf(stderr, "luxel-bench: computing reference %s (%s)\n", maps.hash.c_str(),
                 maps.key.c_str());
    Stopwatch clock;
    const ReferenceSettings settings = reference_settings(spec);
    ReferenceIntegrator integrator(scene, settings);
    for (std::uint32_t pass = 0; pass < kPasses; ++pass) {
        integrator.set_pass_size(static_cast<std::uint32_t>(share(spec.spp, pass)),
                                 share(spec.caustic_photons, pass));
        integrator.set_indirect_photons_per_pass(share(spec.indirect_photons, pass));
        integrator.run_pass(jobs);
    }
    maps.seconds = clock.elapsed_ms() / 1000.0;
    maps.area = scene.texel_areas();
    for (std::size_t c = 0; c < 3; ++c) {
        maps.value[c] = integrator.irradiance(static_cast<Component>(c));
        maps.relative_standard_error[c] =
            integrator.relative_standard_error(static_cast<Component>(c));
    }
    save(file, maps);
    std::fprintf(stderr,
                 "luxel-bench: reference %s computed in %.1f s (rel. std. error indirect %.4f, "
                 "caustic %.4f)\n",
                 maps.hash.c_str(), maps.seconds, maps.relative_standard_error[1],
                 maps.relative_standard_error[2]);
    return maps;
}

}  // namespace luxel::bench
