#include "luxel/lighting/gpu/caustic_kernel.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "luxel/runtime/error.hpp"

namespace luxel::lighting {

const char* kernel_name(CausticKernel kernel) {
    switch (kernel) {
        case CausticKernel::Larsen:
            return "larsen";
        case CausticKernel::Box:
            return "box";
        case CausticKernel::RoundCone:
            return "round_cone";
        case CausticKernel::WorldCone:
            return "world_cone";
        case CausticKernel::MipLevels:
            return "mip_levels";
        case CausticKernel::PhotonFootprints:
            return "photon_footprints";
    }
    return "unknown";
}

std::vector<float> caustic_kernel_weights(CausticKernel kernel, int k) {
    if (k < 0 || k > kMaxCausticKernelRadius) {
        throw Error("caustic kernel radius must be in [0, " +
                    std::to_string(kMaxCausticKernelRadius) + "], got " + std::to_string(k));
    }
    if (kernel == CausticKernel::WorldCone || kernel == CausticKernel::MipLevels ||
        kernel == CausticKernel::PhotonFootprints) {
        throw Error(std::string("the ") + kernel_name(kernel) +
                    " caustic kernel has no fixed weights");
    }
    const int size = 2 * k + 1;
    std::vector<double> w(static_cast<std::size_t>(size * size));
    double sum = 0.0;
    for (int j = -k; j <= k; ++j) {
        for (int i = -k; i <= k; ++i) {
            const double r2 = static_cast<double>(i * i + j * j);
            double value = 1.0;
            if (kernel == CausticKernel::Larsen) {
                value = std::sqrt(1.0 + 2.0 * k * k - r2);
            } else if (kernel == CausticKernel::RoundCone) {
                value = std::max(0.0, 1.0 - std::sqrt(r2) / (k + 1.0));
            }
            w[static_cast<std::size_t>((j + k) * size + i + k)] = value;
            sum += value;
        }
    }
    // Normalised in double so the float weights sum to 1 within rounding.
    std::vector<float> result(w.size());
    for (std::size_t n = 0; n < w.size(); ++n) {
        result[n] = static_cast<float>(w[n] / sum);
    }
    return result;
}

}  // namespace luxel::lighting
