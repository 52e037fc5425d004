#include "luxel/prep/options.hpp"

#include <string>

#include "luxel/runtime/error.hpp"
#include "luxel/scene/lightmap_layout.hpp"

namespace luxel::prep {

void validate(const PrepOptions& options) {
    if (!(options.texel_size > 1e-6 && options.texel_size <= 1e6)) {
        throw Error("--texel-size must be a positive number of metres (1e-6 to 1e6), got " +
                    std::to_string(options.texel_size));
    }
    if (options.min_texels_across < 0 || options.min_texels_across > 1024) {
        throw Error("--min-texels-across must be within 0..1024 texels (0: off), got " +
                    std::to_string(options.min_texels_across));
    }
    if (options.texel_budget > kMaxTexelBudget) {
        throw Error("--texel-budget must be within 0..2^40 texels (0: no budget), got " +
                    std::to_string(options.texel_budget));
    }
    if (!(options.hidden_texel_scale >= 1.0 && options.hidden_texel_scale <= 64.0)) {
        throw Error("--hidden-texel-scale must be within 1..64 (1: off), got " +
                    std::to_string(options.hidden_texel_scale));
    }
    if (!(options.crease_degrees >= 0.0 && options.crease_degrees <= 180.0)) {
        throw Error("--crease-deg must be within 0..180 degrees, got " +
                    std::to_string(options.crease_degrees));
    }
    if (options.padding < 0 || options.padding > 64) {
        throw Error("--padding must be within 0..64 texels, got " +
                    std::to_string(options.padding));
    }
    const std::string max = std::to_string(scene::kMaxLightmapPageSize);
    if (options.page_size != 0 && (options.page_size < 2 * options.padding + 1 ||
                                   options.page_size > scene::kMaxLightmapPageSize)) {
        throw Error("--page-size must be 0 (automatic) or within " +
                    std::to_string(2 * options.padding + 1) + ".." + max + " texels, got " +
                    std::to_string(options.page_size));
    }
    if (options.auto_page_limit < 2 * options.padding + 1 ||
        options.auto_page_limit > scene::kMaxLightmapPageSize) {
        throw Error("the automatic page size limit must be within " +
                    std::to_string(2 * options.padding + 1) + ".." + max + " texels");
    }
    if (!(options.surface_texel_budget >= 1.0) || !(options.max_stretch > 1.0)) {
        throw Error("the surface texel budget must be >= 1 and the stretch bound > 1");
    }
    if (options.threads < 0) {
        throw Error("--threads must not be negative, got " + std::to_string(options.threads));
    }
}

}  // namespace luxel::prep
