#include "image_reference.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

#include "luxel/lighting/reference/caustic_pixels.hpp"
#include "luxel/lighting/reference/reference_integrator.hpp"
#include "luxel/runtime/clock.hpp"
#include "luxel/runtime/error.hpp"
#include "reference_cache.hpp"

namespace luxel::bench {
namespace {

using namespace lighting::reference;

constexpr std::uint32_t kPasses = 4;  ///< as luxel-ref's default: progress after each

std::uint64_t share(std::uint64_t total, std::uint32_t pass) {
    return total / kPasses + (pass < total % kPasses ? 1 : 0);
}

bool load(const std::filesystem::path& stem, ReferenceImage& reference, int width, int height) {
    std::ifstream in(stem.string() + ".json");
    if (!in) {
        return false;
    }
    try {
        const nlohmann::json json = nlohmann::json::parse(in);
        if (json.at("key").get<std::string>() != reference.key) {
            return false;  // a hash collision, or an older format
        }
        reference.seconds = json.at("seconds").get<double>();
        reference.relative_standard_error = json.at("relative_standard_error").get<double>();
        reference.caustic_pixels_se =
            json.at("caustic_pixels_relative_standard_error").get<double>();
        reference.image = read_exr(stem.string() + ".exr");
        reference.caustic_pixels = read_exr(stem.string() + ".caustic.exr");
    } catch (const nlohmann::json::exception&) {
        return false;  // unreadable: computed again and overwritten
    } catch (const Error&) {
        return false;  // the EXR is missing or damaged: the same
    }
    return reference.image.width == width && reference.image.height == height &&
           reference.caustic_pixels.width == width && reference.caustic_pixels.height == height;
}

void save(const std::filesystem::path& stem, const ReferenceImage& reference) {
    std::filesystem::create_directories(stem.parent_path());
    // The EXR first, the JSON that vouches for it last (each written beside and renamed): a run
    // killed in between leaves an entry that does not load, never a wrong one.
    const std::filesystem::path exr = stem.string() + ".exr";
    const std::filesystem::path json_file = stem.string() + ".json";
    const std::filesystem::path partial_exr = stem.string() + ".partial.exr";
    write_exr(partial_exr, reference.image);
    std::filesystem::rename(partial_exr, exr);
    write_exr(partial_exr, reference.caustic_pixels);
    std::filesystem::rename(partial_exr, stem.string() + ".caustic.exr");
    nlohmann::json json;
    json["key"] = reference.key;
    json["seconds"] = reference.seconds;
    json["relative_standard_error"] = reference.relative_standard_error;
    json["caustic_pixels_relative_standard_error"] = reference.caustic_pixels_se;
    const std::filesystem::path partial_json = stem.string() + ".partial.json";
    {
        std::ofstream out(partial_json);
        out << json.dump(2) << "\n";
        if (!out) {
            throw Error("cannot write " + partial_json.string());
        }
    }
    std::filesystem::rename(partial_json, json_file);
}

}  // namespace

std::string describe_camera(const ReferenceCamera& camera) {
    std::ostringstream out;
    out.precision(9);  // every float digit: a camera moved by a rounding step is another camera
    out << "camera=" << camera.width << "x" << camera.height << ":view";
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            out << "," << camera.view[c][r];
        }
    }
    out << ":projection";
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            out << "," << camera.projection[c][r];
        }
    }
    return out.str();
}

ReferenceImage reference_image_for(const std::filesystem::path& cache_dir, const std::string& pose,
                                   const ReferenceScene& scene, const ReferenceCamera& camera,
                                   const ReferenceSpec& spec, const ImageSpec& image,
                                   JobSystem& jobs) {
    ReferenceImage reference;
    // frame=v3: glass and water enclose nothing (ReferenceScene's hidden points), so a pool's
    // floor seen through its water is lit. v4: the caustic term at pixel resolution beside it.
    // v5: paths scale radiance across a closed solid's faces and absorb inside it to a diffuse
    // surface (refracted_radiance_scale, ClosedMedium).
    reference.key = pose + ";" + describe_camera(camera) +
                    ";image_spp=" + std::to_string(image.spp) +
                    ";caustic_photons=" + std::to_string(spec.caustic_photons) +
                    ";seed=" + std::to_string(spec.seed) + ";frame=v5";
    // Paths read base-colour textures per hit (HitTextures): a textured level gets a new
    // entry; an untextured one keeps its cached frame.
    if (scene.textured()) {
        reference.key += ";textures=per-hit";
    }
    reference.hash = cache_hash(reference.key);
    const std::filesystem::path stem = cache_dir / (reference.hash + ".frame");
    if (load(stem, reference, camera.width, camera.height)) {
        reference.from_cache = true;
        std::fprintf(stderr,
                     "luxel-bench: reference frame %s from cache (computed in %.1f s; rel. std. "
                     "error %.4f)\n",
                     reference.hash.c_str(), reference.seconds, reference.relative_standard_error);
        return reference;
    }
    std::fprintf(stderr, "luxel-bench: computing reference frame %s (%dx%d, %u spp)\n",
                 reference.hash.c_str(), camera.width, camera.height, image.spp);
    Stopwatch clock;
    // As luxel-ref renders a frame: the integrator traces only caustic photons (no texel
    // samples, no indirect photons), and the frame's diffuse surfaces read their estimate.
    const ReferenceSettings settings = reference_settings(spec);
    ReferenceIntegrator integrator(scene, settings);
    ReferenceFrameSettings frame_settings;
    frame_settings.seed = spec.seed;
    frame_settings.paths = settings.paths;
    ReferenceFrame frame(scene, camera, frame_settings);
    // The same photons at pixel resolution (the close-up error, --caustic-pixels): a hash
    // lookup per caustic photon beside its texel.
    const CausticPixels pixels = caustic_pixels(scene, camera);
    integrator.set_caustic_footprints(pixels.footprints);
    for (std::uint32_t pass = 0; pass < kPasses; ++pass) {
        integrator.set_pass_size(0, share(spec.caustic_photons, pass));
        integrator.set_indirect_photons_per_pass(0);
        integrator.run_pass(jobs);
        const auto samples = static_cast<std::uint32_t>(share(image.spp, pass));
        if (samples > 0) {
            frame.set_samples_per_pass(samples);
            frame.run_pass(jobs, integrator.caustics().irradiance_all());
        }
    }
    reference.seconds = clock.elapsed_ms() / 1000.0;
    reference.image = frame.image();
    reference.relative_standard_error = frame.relative_standard_error();
    reference.caustic_pixels = caustic_pixel_image(pixels, integrator.caustics());
    reference.caustic_pixels_se =
        caustic_pixels_relative_standard_error(pixels, integrator.caustics());
    save(stem, reference);
    std::fprintf(stderr,
                 "luxel-bench: reference frame %s computed in %.1f s (rel. std. error %.4f)\n",
                 reference.hash.c_str(), reference.seconds, reference.relative_standard_error);
    return reference;
}

double net_of_reference_noise(double relrmse, double reference_se) {
    const double s2 = reference_se * reference_se;
    if (!std::isfinite(relrmse) || !(s2 < 1.0)) {
        return std::numeric_limits<double>::infinity();
    }
    return std::sqrt(std::max(0.0, (relrmse * relrmse - s2) / (1.0 - s2)));
}

void write_side_by_side(const std::filesystem::path& path, const Image& real_time,
                        const Image& reference) {
    if (real_time.width != reference.width || real_time.height != reference.height) {
        throw Error(path.string() + ": the real-time frame is " + std::to_string(real_time.width) +
                    "x" + std::to_string(real_time.height) + ", the reference " +
                    std::to_string(reference.width) + "x" + std::to_string(reference.height));
    }
    constexpr int kGap = 4;  ///< black pixels between the two
    const int w = reference.width;
    Image both(2 * w + kGap, reference.height, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    for (int y = 0; y < reference.height; ++y) {
        for (int x = 0; x < w; ++x) {
            both.set_pixel(x, y, real_time.pixel(x, y));
            both.set_pixel(w + kGap + x, y, reference.pixel(x, y));
        }
    }
    ToneMapSettings tone;
    tone.exposure = metered_exposure(reference);
    write_png(path, both, tone);
}

}  // namespace luxel::bench
