// libFuzzer target for the glTF loader: any input must either load into a scene that passes
// Scene::validate() (and can be written again) or be rejected with a luxel::Error. Any other
// exception escapes and aborts, which libFuzzer reports like a crash or a sanitizer finding.
// Built only with LUXEL_FUZZ=ON and clang; run it with scripts/fuzz.sh.

#include <cstddef>
#include <cstdint>
#include <span>

#include "luxel/runtime/error.hpp"
#include "luxel/runtime/log.hpp"
#include "luxel/scene/gltf.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    // Warnings about broken inputs are the point here, not news.
    static const bool quiet = [] {
        luxel::log::set_level(luxel::log::Level::Off);
        return true;
    }();
    (void)quiet;

    // Limits sized for fuzzing: generous for the seeds, small enough that a legal but huge
    // input cannot spend the run allocating.
    luxel::scene::LoadOptions options;
    options.max_file_size = std::uint64_t{1} << 22;
    options.max_accessor_elements = std::uint64_t{1} << 20;
    options.max_total_triangles = std::uint64_t{1} << 20;
    options.max_nodes = std::size_t{1} << 14;

    try {
        const luxel::scene::Scene scene = luxel::scene::load_gltf_from_memory(
            std::span<const std::uint8_t>(data, size), "fuzz-input", {}, options);
        scene.validate();
        (void)scene.world_matrices();
        const auto written =
            luxel::scene::save_gltf_to_memory(scene, luxel::scene::GltfContainer::Binary);
        (void)luxel::scene::load_gltf_from_memory(written, "fuzz-input (rewritten)", {}, options);
    } catch (const luxel::Error&) {
        // A clean rejection is a correct answer.
    }
    return 0;
}
