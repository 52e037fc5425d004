#include "luxel/lighting/core/iim_page.hpp"

#include <algorithm>
#include <cmath>

namespace luxel::lighting {

static_assert(sizeof(IimFade) == 2 * sizeof(float),
              "the renderer uploads the fades as a two-channel float texture");

IimPage::IimPage(int page_size)
    : previous(page_size), current(page_size), fades(previous.texels.size()) {}

glm::vec3 IimPage::shown(int x, int y, double now_seconds) const {
    const std::size_t index = static_cast<std::size_t>(y) * static_cast<std::size_t>(current.size) +
                              static_cast<std::size_t>(x);
    const IimFade& fade = fades[index];
    const double elapsed = now_seconds - static_cast<double>(fade.committed_seconds);
    const double seconds = static_cast<double>(fade.fade_seconds);
    // A fade of zero (or a clock that went backwards) shows the new value at once.
    const double weight = seconds > 0.0 ? std::clamp(elapsed / seconds, 0.0, 1.0) : 1.0;
    return glm::mix(previous.texels[index], current.texels[index], static_cast<float>(weight));
}

void IimPage::commit(int x, int y, const glm::vec3& value, double now_seconds,
                     double fade_seconds) {
    const std::size_t index = static_cast<std::size_t>(y) * static_cast<std::size_t>(current.size) +
                              static_cast<std::size_t>(x);
    previous.texels[index] = shown(x, y, now_seconds);
    current.texels[index] = value;
    double seconds = std::isfinite(fade_seconds) ? std::max(fade_seconds, 0.0) : 0.0;
    // A texel still in a shorter fade keeps that fade's end: a local pass's texel (fading in
    // over the change blend) that a photon-driven pass commits again a frame later heads for
    // the new value by the same moment, instead of restarting the slow fade from the old
    // light it has barely left.
    const IimFade& old = fades[index];
    const double old_end =
        static_cast<double>(old.committed_seconds) + static_cast<double>(old.fade_seconds);
    if (static_cast<double>(old.fade_seconds) < seconds && old_end > now_seconds) {
        seconds = old_end - now_seconds;
    }
    fades[index] = {static_cast<float>(now_seconds), static_cast<float>(seconds)};
}

}  // namespace luxel::lighting
