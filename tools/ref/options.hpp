#pragma once

// luxel-ref's command line, parsed and checked.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "luxel/prep/auto_prep.hpp"
#include "luxel/scene/gltf.hpp"

namespace luxel::ref {

/// --camera x,y,z:tx,ty,tz:fov (fov: vertical, degrees).
struct CameraSpec {
    glm::vec3 eye{0.0f};
    glm::vec3 target{0.0f, 0.0f, -1.0f};
    float fov_degrees = 60.0f;
};

struct Options {
    std::string level;  ///< a prepared level's name or a .glb/.gltf path
    double time = 0.0;
    std::optional<CameraSpec> camera;
    int width = 640;
    int height = 480;
    std::uint32_t spp = 64;
    std::uint32_t passes = 4;
    std::uint64_t photons = 10'000'000;
    std::uint32_t seed = 1;
    std::uint32_t max_vertices = 10'000;
    int threads = 0;
    std::filesystem::path image;      ///< -o: EXR of the camera
    std::filesystem::path lightmaps;  ///< --lightmaps: .json, or .exr pages
    std::filesystem::path preview;    ///< --png: tone-mapped preview of the frame
    /// --caustic-pixels: EXR of the camera's caustic term alone, at pixel resolution.
    std::filesystem::path caustic_pixels;
    bool no_caustic_bounce = false;
    /// --indirect: "photons" (IndirectPhotons, texel-binned) or "paths" (NEE at every vertex).
    std::string indirect = "photons";
    std::uint64_t indirect_photons = 20'000'000;  ///< in all, over the passes
    scene::LoadOptions load_limits;               ///< --limit
    std::optional<scene::SkySpec> sky;            ///< --sky: instead of the level's
    prep::AutoPrepSettings auto_prep;             ///< --no-auto-prep, --prep-cache
};

/// Parses --camera's value; throws luxel::Error naming the flag and what is wrong.
[[nodiscard]] CameraSpec parse_camera(const std::string& text);

/// Checks what CLI11 cannot: at least one output, sizes, passes. Throws luxel::Error.
void validate(const Options& options);

}  // namespace luxel::ref
