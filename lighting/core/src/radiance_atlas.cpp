#include "luxel/lighting/core/radiance_atlas.hpp"

#include <algorithm>
#include <cmath>

namespace luxel::lighting {

RadiancePage::RadiancePage(int page_size)
    : size(std::max(page_size, 0)),
      texels(static_cast<std::size_t>(size) * static_cast<std::size_t>(size), glm::vec3(0.0f)) {}

void RadiancePage::mark_changed(const scene::TexelRect& rect) {
    if (rect.width <= 0 || rect.height <= 0) {
        return;
    }
    ++version;
    log.push_back({version, rect});
    if (log.size() > kLogLength) {
        log.pop_front();
    }
}

PageChanges RadiancePage::changes_since(std::uint64_t reader_version) const {
    PageChanges changes;
    if (reader_version >= version) {
        return changes;
    }
    // The log must hold every change after the reader's version, the first being
    // reader_version + 1; a page whose version was set without a log entry, or a reader that
    // fell behind the log, reads everything.
    if (log.empty() || log.front().version > reader_version + 1) {
        changes.everything = true;
        return changes;
    }
    int x0 = 0;
    int y0 = 0;
    int x1 = 0;
    int y1 = 0;
    bool first = true;
    for (const PageChange& change : log) {
        if (change.version <= reader_version) {
            continue;
        }
        const scene::TexelRect& r = change.rect;
        x0 = first ? r.x : std::min(x0, r.x);
        y0 = first ? r.y : std::min(y0, r.y);
        x1 = first ? r.x + r.width : std::max(x1, r.x + r.width);
        y1 = first ? r.y + r.height : std::max(y1, r.y + r.height);
        first = false;
    }
    changes.rect = {x0, y0, x1 - x0, y1 - y0};
    return changes;
}

glm::vec3 RadiancePage::sample(const glm::vec2& uv) const {
    if (size <= 0 || !std::isfinite(uv.x) || !std::isfinite(uv.y)) {
        return glm::vec3(0.0f);
    }
    const float extent = static_cast<float>(size);
    // Texel centres sit at integer + 0.5; clamp so both taps stay on the page.
    const float fx = std::clamp(uv.x * extent - 0.5f, 0.0f, extent - 1.0f);
    const float fy = std::clamp(uv.y * extent - 0.5f, 0.0f, extent - 1.0f);
    const int x0 = static_cast<int>(fx);
    const int y0 = static_cast<int>(fy);
    const int x1 = std::min(x0 + 1, size - 1);
    const int y1 = std::min(y0 + 1, size - 1);
    const float tx = fx - static_cast<float>(x0);
    const float ty = fy - static_cast<float>(y0);
    const glm::vec3 top = glm::mix(at(x0, y0), at(x1, y0), tx);
    const glm::vec3 bottom = glm::mix(at(x0, y1), at(x1, y1), tx);
    return glm::mix(top, bottom, ty);
}

glm::vec3 RadianceAtlas::sample(std::int32_t surface, const glm::vec2& uv) const {
    if (surface < 0) {
        return glm::vec3(0.0f);
    }
    const auto index = static_cast<std::size_t>(surface);
    glm::vec3 radiance =
        index < surface_emission.size() ? surface_emission[index] : glm::vec3(0.0f);
    if (index < surface_page.size()) {
        const std::int32_t page = surface_page[index];
        if (page >= 0 && static_cast<std::size_t>(page) < pages.size()) {
            radiance += pages[static_cast<std::size_t>(page)].sample(uv);
        }
    }
    return radiance;
}

glm::vec3 RadianceAtlas::sky(const glm::vec3& towards_sky) const {
    glm::vec3 radiance(0.0f);
    for (const Sky& one : skies) {
        if (one.radiance != nullptr) {
            radiance += one.radiance->radiance(towards_sky) * one.scale;
        }
    }
    return radiance;
}

}  // namespace luxel::lighting
