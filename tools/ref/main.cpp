// luxel-ref: reference renders of any level at any animation time (docs/METHOD.md §10,
// issue 11).
//   luxel-ref --level NAME|PATH [--time T] [--camera x,y,z:tx,ty,tz:fov] [--width W]
//             [--height H] --spp N [--passes P] [--photons N] [--seed S] [--threads N]
//             [-o OUT.exr] [--lightmaps OUT.json|OUT.exr]
// Progress and each component's relative standard error go to stderr after every pass.

#include <cinttypes>
#include <cstdio>
#include <exception>
#include <iostream>
#include <new>
#include <string>

#include <CLI/CLI.hpp>
#include <glm/trigonometric.hpp>

#include "level.hpp"
#include "lightmap_output.hpp"
#include "luxel/lighting/reference/caustic_pixels.hpp"
#include "luxel/lighting/reference/reference_frame.hpp"
#include "luxel/lighting/reference/reference_integrator.hpp"
#include "luxel/runtime/cli.hpp"
#include "luxel/runtime/clock.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/runtime/image.hpp"
#include "luxel/runtime/jobs.hpp"
#include "luxel/runtime/tool_main.hpp"
#include "luxel/scene/level_check.hpp"
#include "luxel/scene/load_limits_flag.hpp"
#include "luxel/scene/sky_flag.hpp"
#include "options.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting::reference;

/// Spreads `total` over `passes` as evenly as integers allow (the first passes get the rest).
std::uint64_t share(std::uint64_t total, std::uint32_t passes, std::uint32_t pass) {
    return total / passes + (pass < total % passes ? 1 : 0);
}

/// Declares luxel-ref's flags into `options` (the camera as text, parsed after).
void add_flags(CLI::App& app, ref::Options& options, std::string& camera_text) {
    app.add_option("--level", options.level,
                   "a prepared level's name (assets/levels/prepared/NAME.glb) or a .glb path")
        ->required();
    app.add_option("--time", options.time, "animation time in seconds")->capture_default_str();
    app.add_option("--camera", camera_text,
                   "x,y,z:tx,ty,tz:fov (position, target, vertical fov in degrees); default: "
                   "the level's first camera, else the default view " +
                       luxel::scene::describe(luxel::scene::DefaultView{}));
    app.add_option("--width", options.width, "frame width in pixels")->capture_default_str();
    app.add_option("--height", options.height, "frame height in pixels")->capture_default_str();
    app.add_option("--spp", options.spp, "path samples per pixel and per texel, in all")
        ->capture_default_str();
    app.add_option("--passes", options.passes,
                   "progressive passes (progress and standard errors after each)")
        ->capture_default_str();
    app.add_option("--photons", options.photons,
                   "caustic photons in all, over every (delta light, specular object) pair")
        ->capture_default_str();
    app.add_option("--indirect", options.indirect,
                   "indirect component: photons (texel-binned photon estimate, fast where a "
                   "light is close to a wall) or paths (NEE at every diffuse vertex)")
        ->capture_default_str();
    app.add_option("--indirect-photons", options.indirect_photons,
                   "photons for the indirect component in all (--indirect photons)")
        ->capture_default_str();
    app.add_option("--seed", options.seed, "random seed (the result is fixed by it)")
        ->capture_default_str();
    app.add_option("--max-vertices", options.max_vertices, "longest path (scattering events)")
        ->capture_default_str();
    cli::add_threads(app, options.threads);
    cli::add_load_limits(app, options.load_limits);
    cli::add_sky(app, options.sky);
    prep::add_auto_prep_flags(app, options.auto_prep);
    app.add_option("-o,--output", options.image, "the frame as OpenEXR (linear RGB radiance)");
    app.add_option("--png", options.preview, "also a tone-mapped PNG preview of the frame");
    app.add_flag("--no-caustic-bounce", options.no_caustic_bounce,
                 "leave out delta-light caustics reflected onward by diffuse surfaces");
    app.add_option("--caustic-pixels", options.caustic_pixels,
                   "the camera's caustics from point, spot and directional lights alone, at pixel "
                   "resolution (each pixel: albedo / pi times the caustic irradiance over the "
                   "patch it sees), as OpenEXR; -o's frame shows them at light-map texels");
    app.add_option("--lightmaps", options.lightmaps,
                   "per-texel irradiance: .json, or .exr (one file per page and component)");
}

/// The frame's camera: --camera, else the level's first; none when no frame is asked for.
std::optional<ReferenceCamera> frame_camera(const ref::Options& options,
                                            const ref::LoadedLevel& level) {
    if (options.image.empty() && options.caustic_pixels.empty()) {
        return std::nullopt;
    }
    if (options.camera) {
        return ReferenceCamera::look_at(options.camera->eye, options.camera->target,
                                        glm::radians(options.camera->fov_degrees), options.width,
                                        options.height);
    }
    // A level without a camera is seen from the default view, as luxel-sandbox sees it; the
    // warning at load (scene::check_level) says which.
    std::optional<ReferenceCamera> camera = ref::level_camera(level, options.width, options.height);
    return camera ? camera : ref::default_camera(options.width, options.height);
}

ReferenceSettings integrator_settings(const ref::Options& options) {
    // The caustic photons serve both outputs: the light maps' caustic component, and the
    // frame's diffuse surfaces (caustics from delta lights that paths cannot find).
    ReferenceSettings settings;
    settings.seed = options.seed;
    settings.caustics.seed = options.seed;
    settings.paths.max_vertices = options.max_vertices;
    settings.paths.caustic_bounce = !options.no_caustic_bounce;
    settings.indirect =
        options.indirect == "paths" ? IndirectMethod::Paths : IndirectMethod::Photons;
    settings.indirect_photons.seed = options.seed;
    settings.indirect_photons.max_vertices = options.max_vertices;
    return settings;
}

/// The progressive passes, each reporting its time and the standard errors so far.
void run_passes(const ref::Options& options, ReferenceIntegrator& integrator,
                std::optional<ReferenceFrame>& frame, JobSystem& jobs) {
    const bool lightmaps = !options.lightmaps.empty();
    for (std::uint32_t pass = 0; pass < options.passes; ++pass) {
        Stopwatch pass_clock;
        CausticReferenceSettings photons;
        photons.photons_per_pass = share(options.photons, options.passes, pass);
        photons.seed = options.seed;
        const auto samples = static_cast<std::uint32_t>(share(options.spp, options.passes, pass));
        // Without --lightmaps the integrator only traces the photons the frame needs.
        integrator.set_pass_size(lightmaps ? samples : 0, photons.photons_per_pass);
        integrator.set_indirect_photons_per_pass(
            lightmaps ? share(options.indirect_photons, options.passes, pass) : 0);
        integrator.run_pass(jobs);
        if (frame && samples > 0) {
            frame->set_samples_per_pass(samples);
            const std::vector<glm::dvec3> caustics = integrator.caustics().irradiance_all();
            frame->run_pass(jobs, caustics);
        }
        std::fprintf(stderr, "luxel-ref: pass %u/%u (%.1f s)", pass + 1, options.passes,
                     pass_clock.elapsed_ms() / 1000.0);
        if (lightmaps) {
            std::fprintf(stderr, ": rel. std. error direct %.4f, indirect %.4f, caustic %.4f",
                         integrator.relative_standard_error(Component::Direct),
                         integrator.relative_standard_error(Component::Indirect),
                         integrator.relative_standard_error(Component::Caustic));
        }
        if (frame) {
            std::fprintf(stderr, "%s frame %.4f", lightmaps ? "," : ": rel. std. error",
                         frame->relative_standard_error());
        }
        std::fprintf(stderr, "\n");
    }
}

void write_outputs(const ref::Options& options, const ReferenceIntegrator& integrator,
                   const std::optional<ReferenceFrame>& frame,
                   const std::optional<CausticPixels>& pixels, double seconds) {
    if (pixels) {
        const Image image = caustic_pixel_image(*pixels, integrator.caustics());
        write_exr(options.caustic_pixels, image);
        std::fprintf(stderr,
                     "luxel-ref: wrote %s (%dx%d, caustics at %zu pixels' footprints, %" PRIu64
                     " photons per pair)\n",
                     options.caustic_pixels.string().c_str(), image.width, image.height,
                     pixels->footprints.size(), integrator.caustics().photons_per_pair());
    }
    if (frame) {
        const Image image = frame->image();
        write_exr(options.image, image);
        if (!options.preview.empty()) {
            write_png(options.preview, image);
        }
        std::fprintf(stderr, "luxel-ref: wrote %s (%dx%d, %" PRIu64 " spp)\n",
                     options.image.string().c_str(), image.width, image.height, frame->samples());
    }
    if (!options.lightmaps.empty()) {
        if (options.lightmaps.extension() == ".json") {
            ref::write_lightmaps_json(options.lightmaps, integrator,
                                      {options.level, options.time, options.seed, seconds});
            std::fprintf(stderr, "luxel-ref: wrote %s\n", options.lightmaps.string().c_str());
        } else {
            const std::size_t files = ref::write_lightmap_pages(options.lightmaps, integrator);
            std::fprintf(stderr, "luxel-ref: wrote %zu page images beside %s\n", files,
                         options.lightmaps.string().c_str());
        }
    }
}

int run(int argc, char** argv) {
    CLI::App app{
        "luxel-ref: the reference integrator (path tracing with next-event estimation, and a "
        "dense photon estimate for caustics from point, spot and directional lights). Writes a "
        "linear HDR frame of a camera and/or per-texel reference irradiance of every "
        "light-mapped surface, split into direct, indirect and caustic, with standard errors."};
    ref::Options options;
    std::string camera_text;
    add_flags(app, options, camera_text);
    if (!cli::parse(app, argc, argv)) {
        return 0;
    }
    cli::check_usage([&] {
        if (!camera_text.empty()) {
            options.camera = ref::parse_camera(camera_text);
        }
        ref::validate(options);
    });

    const std::filesystem::path file = ref::resolve_level(options.level);
    JobSystem jobs(options.threads);
    Stopwatch clock;
    // What the level lacks, in luxel-sandbox's words (only a frame without --camera is seen
    // through the level's camera), and the level prepared at load if luxel-prep never did.
    prep::PlayableLevel playable{options.load_limits, {}, options.auto_prep};
    playable.check.uses_camera =
        (!options.image.empty() || !options.caustic_pixels.empty()) && !options.camera;
    const auto level = ref::load_level(file, options.time, options.sky, playable, jobs);
    const ReferenceScene& scene = *level->scene;
    std::fprintf(stderr,
                 "luxel-ref: %s at t = %.3f s: %zu light-mapped surfaces, %zu texels, %zu "
                 "lights, %zu specular objects (%.1f s to load)\n",
                 file.string().c_str(), options.time, scene.surfaces().size(), scene.texel_count(),
                 scene.lights().size(), scene.generator_spheres().size(),
                 clock.elapsed_ms() / 1000.0);
    const std::optional<ReferenceCamera> camera = frame_camera(options, *level);

    ReferenceIntegrator integrator(scene, integrator_settings(options));
    ReferenceFrameSettings frame_settings;
    frame_settings.seed = options.seed;
    frame_settings.paths = integrator_settings(options).paths;
    std::optional<ReferenceFrame> frame;
    if (camera && !options.image.empty()) {
        frame.emplace(scene, *camera, frame_settings);
    }
    std::optional<CausticPixels> pixels;
    if (camera && !options.caustic_pixels.empty()) {
        pixels = caustic_pixels(scene, *camera);
        integrator.set_caustic_footprints(pixels->footprints);
    }
    run_passes(options, integrator, frame, jobs);
    write_outputs(options, integrator, frame, pixels, clock.elapsed_ms() / 1000.0);
    std::fprintf(stderr, "luxel-ref: done in %.1f s\n", clock.elapsed_ms() / 1000.0);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return luxel::run_tool("luxel-ref", run, argc, argv);
}
