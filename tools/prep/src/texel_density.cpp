#include "luxel/prep/texel_density.hpp"

#include <algorithm>
#include <cmath>

#include "luxel/runtime/error.hpp"

namespace luxel::prep {

namespace {

constexpr double kMinTexelSize = 1e-6;
constexpr double kMaxTexelSize = 1e6;
/// How much finer than its own size a node's texels may become to keep a width's texels.
constexpr double kMaxRefinement = 8.0;

/// The middle of three extents: a box's width once its thickness is set aside.
double width_of(const glm::dvec3& size) {
    return std::max(std::min(size.x, size.y), std::min(std::max(size.x, size.y), size.z));
}

}  // namespace

std::vector<double> node_texel_sizes(std::span<const NodeExtent> nodes,
                                     const PrepOptions& options) {
    std::vector<double> sizes;
    sizes.reserve(nodes.size());
    double texels = 0.0;
    for (const NodeExtent& node : nodes) {
        const double chosen = options.texel_size * node.texel_scale;
        double size = chosen;
        const double width = width_of(node.size);
        if (options.min_texels_across > 0 && width > 0.0 && std::isfinite(width)) {
            size = std::min(size,
                            std::max(width / options.min_texels_across, chosen / kMaxRefinement));
        }
        size = std::clamp(size, kMinTexelSize, kMaxTexelSize);
        sizes.push_back(size);
        texels += node.area / (size * size);
    }
    if (options.texel_budget > 0 && texels > static_cast<double>(options.texel_budget)) {
        const double coarser = std::sqrt(texels / static_cast<double>(options.texel_budget));
        for (double& size : sizes) {
            size = std::clamp(size * coarser, kMinTexelSize, kMaxTexelSize);
        }
    }
    return sizes;
}

double texel_scale_of(const scene::Node& node, const std::string& where) {
    const nlohmann::json& raw = node.flags.raw;
    if (!raw.is_object() || !raw.contains("texel_scale")) {
        return 1.0;
    }
    const nlohmann::json& value = raw.at("texel_scale");
    const double scale = value.is_number() ? value.get<double>() : 0.0;
    if (!(scale >= 1.0 / 64.0 && scale <= 64.0)) {
        throw Error(where +
                    ": extras.luxel.texel_scale must be a number within 1/64..64 (the "
                    "node's texel size over --texel-size), got " +
                    value.dump());
    }
    return scale;
}

}  // namespace luxel::prep
