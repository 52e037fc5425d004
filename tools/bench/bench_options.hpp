#pragma once

// luxel-bench's command line, parsed and checked.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/prep/auto_prep.hpp"
#include "luxel/scene/gltf.hpp"
#include "options.hpp"

namespace luxel::bench {

/// One --sweep KNOB=V1,V2,...: the knob and its values as given (checked by parse_sweep).
struct Sweep {
    std::string knob;
    std::vector<std::string> values;
};

/// The scripted change: a node moved by an offset once the static run has converged.
/// The scripted change after the static frames: a node moved (NODE:dx,dy,dz), turned
/// (NODE:turn=ax,ay,az,degrees, about its own origin) or its light switched (NODE:off, NODE:on).
struct Change {
    enum class Kind { Move, Turn, Off, On };
    std::string node;
    Kind kind = Kind::Move;
    glm::vec3 offset{0.0f};            ///< Move: metres
    glm::vec3 axis{0.0f, 1.0f, 0.0f};  ///< Turn
    float degrees = 0.0f;              ///< Turn
};

/// The reference's size: what the cache key holds besides the level and the pose.
struct ReferenceSpec {
    std::uint64_t indirect_photons = 100'000'000;
    std::uint64_t caustic_photons = 10'000'000;
    std::uint32_t spp = 16;  ///< path samples per texel (direct component, area-light caustics)
    std::uint32_t seed = 1;
};

/// The image error (docs/METHOD.md §10.2): the real-time frame of the level's camera against a
/// reference frame of the same camera and size, at every checkpoint.
struct ImageSpec {
    bool enabled = true;  ///< --no-image: off, and no GL context unless backend=gpu is swept
    int width = 160;      ///< small: a 128-spp reference frame costs about half a minute
    int height = 120;
    std::uint32_t spp = 128;  ///< the reference frame's path samples per pixel
    /// --camera (luxel-ref's syntax): both frames from here instead of the level's first camera.
    std::optional<ref::CameraSpec> camera;
    /// --caustic-pixels: also the frame's caustic term alone against the reference's caustic
    /// at pixel resolution (luxel-ref --caustic-pixels), over the pixels that see a diffuse
    /// surface directly: the error a close-up shows.
    bool caustic_pixels = false;
};

struct Options {
    std::string level;
    scene::LoadOptions load_limits;     ///< --limit
    std::optional<scene::SkySpec> sky;  ///< --sky: instead of the level's
    prep::AutoPrepSettings auto_prep;   ///< --no-auto-prep, --prep-cache
    /// --no-light-map NODE: these nodes' meshes lose their light maps (receivers the irradiance
    /// probes light, issue 26), in the real-time run and the light-map reference alike.
    std::vector<std::string> unmapped;
    std::vector<double> budgets{1.0, 2.0, 4.0, 8.0};
    std::uint32_t frames = 150;  ///< static frames per configuration
    std::uint32_t after = 90;    ///< frames after the scripted change
    /// Frames of the level's animation played after the change, compared at every checkpoint
    /// against a reference of that instant (0: none).
    std::uint32_t animate = 0;
    std::uint32_t checkpoint = 30;  ///< static frames between error measurements
    std::filesystem::path out = "bench-out";
    std::vector<Sweep> sweeps;
    std::string change = "auto";  ///< see Change, "auto" or "none"
    std::optional<Change> parsed_change;
    double time = 0.0;       ///< the animation pose (frozen)
    double dt = 1.0 / 30.0;  ///< seconds per frame (IIM fade-in)
    ReferenceSpec reference;
    ImageSpec image;
    int threads = 0;
    bool dump_maps = false;  ///< per-texel JSON of every run in OUT/maps
};

/// Parses KNOB=V1,V2,... (knobs: budget, photons GxM, aim_n, rays, texels_per_unit, filter,
/// caustics NxK, backend cpu|gpu, kernel larsen|box|cone|world|layer). Throws luxel::Error naming
/// the flag and what is wrong.
[[nodiscard]] Sweep parse_sweep(const std::string& text);
/// Parses NODE:dx,dy,dz. Throws luxel::Error.
[[nodiscard]] Change parse_change(const std::string& text);
/// Parses "1,2,4" into numbers > 0. Throws luxel::Error.
[[nodiscard]] std::vector<double> parse_budgets(const std::string& text);
/// Parses --image WIDTHxHEIGHT (each 1..4096) into `image`. Throws luxel::Error.
void parse_image_size(const std::string& text, ImageSpec& image);
/// Checks ranges CLI11 cannot, and knobs that need the image (kernel) when it is off. Throws
/// luxel::Error.
void validate(const Options& options);

}  // namespace luxel::bench
