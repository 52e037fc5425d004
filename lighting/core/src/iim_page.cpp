#include "luxel/lighting/core/iim_page.hpp"

#include <algorithm>
#include <cmath>

namespace luxel::lighting {

IimPage::IimPage(int page_size)
    : previous(page_size), current(page_size), committed_seconds(previous.texels.size(), -1e30f) {}

glm::vec3 IimPage::shown(int x, int y, double now_seconds, double blend_seconds) const {
    const std::size_t index = static_cast<std::size_t>(y) * static_cast<std::size_t>(current.size) +
                              static_cast<std::size_t>(x);
    const double elapsed = now_seconds - static_cast<double>(committed_seconds[index]);
    // A blend time of zero (or a clock that went backwards) shows the new value at once.
    const double weight = blend_seconds > 0.0 ? std::clamp(elapsed / blend_seconds, 0.0, 1.0) : 1.0;
    return glm::mix(previous.texels[index], current.texels[index], static_cast<float>(weight));
}

void IimPage::commit(int x, int y, const glm::vec3& value, double now_seconds,
                     double blend_seconds) {
    const std::size_t index = static_cast<std::size_t>(y) * static_cast<std::size_t>(current.size) +
                              static_cast<std::size_t>(x);
    previous.texels[index] = shown(x, y, now_seconds, blend_seconds);
    current.texels[index] = value;
    committed_seconds[index] = static_cast<float>(now_seconds);
}

}  // namespace luxel::lighting
