#include "luxel/scene/lightmap_layout.hpp"

#include <string>

#include "luxel/runtime/error.hpp"

namespace luxel::scene {
namespace {

[[noreturn]] void malformed(const std::string& where, const std::string& what) {
    throw Error("extras.luxel.lightmap" + where + ": " + what);
}

const nlohmann::json& member(const nlohmann::json& object, const char* key,
                             const std::string& where) {
    const auto found = object.find(key);
    if (found == object.end()) {
        malformed(where, std::string("missing \"") + key + "\"");
    }
    return *found;
}

std::int64_t integer(const nlohmann::json& object, const char* key, const std::string& where) {
    const auto& value = member(object, key, where);
    if (!value.is_number_integer()) {
        malformed(where + "." + key, "expected an integer");
    }
    return value.get<std::int64_t>();
}

double number(const nlohmann::json& object, const char* key, const std::string& where) {
    const auto& value = member(object, key, where);
    if (!value.is_number()) {
        malformed(where + "." + key, "expected a number");
    }
    return value.get<double>();
}

TexelRect rect(const nlohmann::json& value, int page_size, const std::string& where) {
    if (!value.is_array() || value.size() != 4) {
        malformed(where, "expected [x, y, width, height]");
    }
    std::int64_t v[4];
    for (std::size_t i = 0; i < 4; ++i) {
        if (!value[i].is_number_integer()) {
            malformed(where, "expected integers");
        }
        v[i] = value[i].get<std::int64_t>();
    }
    if (v[0] < 0 || v[1] < 0 || v[2] <= 0 || v[3] <= 0 || v[0] + v[2] > page_size ||
        v[1] + v[3] > page_size) {
        malformed(where, "rectangle outside the " + std::to_string(page_size) + " texel page");
    }
    return {static_cast<int>(v[0]), static_cast<int>(v[1]), static_cast<int>(v[2]),
            static_cast<int>(v[3])};
}

}  // namespace

std::optional<LightmapLayout> read_lightmap_layout(const nlohmann::json& luxel_extras) {
    if (!luxel_extras.is_object()) {
        return std::nullopt;
    }
    const auto found = luxel_extras.find("lightmap");
    if (found == luxel_extras.end()) {
        return std::nullopt;
    }
    const nlohmann::json& object = *found;
    if (!object.is_object()) {
        malformed("", "expected an object");
    }
    LightmapLayout layout;
    const double texel_size = number(object, "texel_size", "");
    if (!(texel_size > 0.0) || texel_size > 1e6) {
        malformed(".texel_size", "must be a positive number of metres");
    }
    layout.texel_size = static_cast<float>(texel_size);
    const std::int64_t page_size = integer(object, "page_size", "");
    if (page_size < 1 || page_size > kMaxLightmapPageSize) {
        malformed(".page_size", "must be within 1.." + std::to_string(kMaxLightmapPageSize));
    }
    layout.page_size = static_cast<int>(page_size);
    const auto& surfaces = member(object, "surfaces", "");
    if (!surfaces.is_array()) {
        malformed(".surfaces", "expected an array");
    }
    for (std::size_t i = 0; i < surfaces.size(); ++i) {
        const std::string where = ".surfaces[" + std::to_string(i) + "]";
        const auto& entry = surfaces[i];
        if (!entry.is_object()) {
            malformed(where, "expected an object");
        }
        LightmapSurface surface;
        const std::int64_t id = integer(entry, "id", where);
        const std::int64_t primitive = integer(entry, "primitive", where);
        const std::int64_t page = integer(entry, "page", where);
        if (id < 0 || id > INT32_MAX || primitive < 0 || primitive > INT32_MAX || page < 0 ||
            page > INT32_MAX) {
            malformed(where, "id, primitive and page must be non-negative 32-bit integers");
        }
        surface.id = static_cast<int>(id);
        surface.primitive = static_cast<int>(primitive);
        surface.page = static_cast<int>(page);
        surface.rect = rect(member(entry, "rect", where), layout.page_size, where + ".rect");
        const auto& charts = member(entry, "charts", where);
        if (!charts.is_array()) {
            malformed(where + ".charts", "expected an array");
        }
        for (std::size_t c = 0; c < charts.size(); ++c) {
            surface.charts.push_back(
                rect(charts[c], layout.page_size, where + ".charts[" + std::to_string(c) + "]"));
        }
        surface.area = number(entry, "area", where);
        surface.texels = integer(entry, "texels", where);
        if (!(surface.area >= 0.0) || surface.texels < 0) {
            malformed(where, "area and texels must not be negative");
        }
        if (entry.contains("texel_size")) {
            surface.texel_size = number(entry, "texel_size", where);
            if (!(surface.texel_size > 0.0) || surface.texel_size > 1e6) {
                malformed(where + ".texel_size", "must be a positive number of metres");
            }
        }
        layout.surfaces.push_back(std::move(surface));
    }
    return layout;
}

nlohmann::json to_json(const LightmapLayout& layout) {
    auto as_array = [](const TexelRect& r) {
        return nlohmann::json::array({r.x, r.y, r.width, r.height});
    };
    nlohmann::json surfaces = nlohmann::json::array();
    for (const auto& surface : layout.surfaces) {
        nlohmann::json charts = nlohmann::json::array();
        for (const auto& chart : surface.charts) {
            charts.push_back(as_array(chart));
        }
        nlohmann::json entry = {{"id", surface.id},
                                {"primitive", surface.primitive},
                                {"page", surface.page},
                                {"rect", as_array(surface.rect)},
                                {"charts", std::move(charts)},
                                {"area", surface.area},
                                {"texels", surface.texels}};
        if (surface.texel_size > 0.0) {
            entry["texel_size"] = surface.texel_size;  // only where it is not the layout's
        }
        surfaces.push_back(std::move(entry));
    }
    return {{"texel_size", layout.texel_size},
            {"page_size", layout.page_size},
            {"surfaces", std::move(surfaces)}};
}

}  // namespace luxel::scene
