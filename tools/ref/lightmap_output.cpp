#include "lightmap_output.hpp"

#include <fstream>
#include <map>

#include <nlohmann/json.hpp>

#include "luxel/runtime/error.hpp"
#include "luxel/runtime/image.hpp"

namespace luxel::ref {
namespace {

using lighting::reference::Component;
using lighting::reference::kComponentCount;

nlohmann::json rgb(const glm::dvec3& v) {
    return nlohmann::json::array({v.x, v.y, v.z});
}

Component component_at(std::size_t c) {
    return static_cast<Component>(c);
}

}  // namespace

void write_lightmaps_json(const std::filesystem::path& file,
                          const lighting::reference::ReferenceIntegrator& integrator,
                          const RunInfo& info) {
    const auto& scene = integrator.scene();
    nlohmann::json out;
    out["level"] = info.level;
    out["time"] = info.time;
    out["seed"] = info.seed;
    out["seconds"] = info.seconds;
    out["samples_per_texel"] = integrator.samples();
    out["caustic_photons"] =
        integrator.caustics().photons_per_pair() * integrator.caustics().pair_count();
    nlohmann::json errors = nlohmann::json::object();
    for (std::size_t c = 0; c < kComponentCount; ++c) {
        errors[component_name(component_at(c))] =
            integrator.relative_standard_error(component_at(c));
    }
    out["relative_standard_error"] = errors;
    nlohmann::json surfaces = nlohmann::json::array();
    for (const auto& surface : scene.surfaces()) {
        nlohmann::json s;
        s["surface"] = surface.surface;
        s["page"] = surface.page;
        s["page_size"] = surface.page_size;
        nlohmann::json xs = nlohmann::json::array();
        nlohmann::json ys = nlohmann::json::array();
        nlohmann::json areas = nlohmann::json::array();
        std::map<std::string, nlohmann::json> columns;
        for (std::size_t i = 0; i < surface.texels.size(); ++i) {
            const auto& texel = surface.texels[i];
            const std::size_t t = surface.first_texel + i;
            xs.push_back(texel.x);
            ys.push_back(texel.y);
            areas.push_back(texel.area);
            for (std::size_t c = 0; c < kComponentCount; ++c) {
                const std::string name = component_name(component_at(c));
                columns[name].push_back(rgb(integrator.irradiance(component_at(c), t)));
                columns[name + "_se"].push_back(rgb(integrator.standard_error(component_at(c), t)));
            }
        }
        s["x"] = std::move(xs);
        s["y"] = std::move(ys);
        s["area"] = std::move(areas);
        for (auto& [name, column] : columns) {
            s[name] = std::move(column);
        }
        surfaces.push_back(std::move(s));
    }
    out["surfaces"] = std::move(surfaces);
    std::error_code ignored;
    if (file.has_parent_path()) {
        std::filesystem::create_directories(file.parent_path(), ignored);
    }
    std::ofstream stream(file);
    stream << out.dump() << "\n";
    if (!stream) {
        throw Error(file.string() + ": cannot write the light maps");
    }
}

std::size_t write_lightmap_pages(const std::filesystem::path& file,
                                 const lighting::reference::ReferenceIntegrator& integrator) {
    const auto& scene = integrator.scene();
    std::map<int, int> page_sizes;
    for (const auto& surface : scene.surfaces()) {
        page_sizes[surface.page] = std::max(page_sizes[surface.page], surface.page_size);
    }
    std::error_code ignored;
    if (file.has_parent_path()) {
        std::filesystem::create_directories(file.parent_path(), ignored);
    }
    const std::filesystem::path stem = file.parent_path() / file.stem();
    std::size_t written = 0;
    for (const auto& [page, size] : page_sizes) {
        for (std::size_t c = 0; c < kComponentCount; ++c) {
            for (const bool error : {false, true}) {
                Image image(size, size, glm::vec4(0.0f));
                for (const auto& surface : scene.surfaces()) {
                    if (surface.page != page) {
                        continue;
                    }
                    for (std::size_t i = 0; i < surface.texels.size(); ++i) {
                        const std::size_t t = surface.first_texel + i;
                        const glm::dvec3 value = error
                                                     ? integrator.standard_error(component_at(c), t)
                                                     : integrator.irradiance(component_at(c), t);
                        image.set_pixel(surface.texels[i].x, surface.texels[i].y,
                                        glm::vec4(glm::vec3(value), 1.0f));
                    }
                }
                const std::string name =
                    std::string(component_name(component_at(c))) + (error ? "_se" : "");
                write_exr(stem.string() + ".page" + std::to_string(page) + "." + name + ".exr",
                          image);
                ++written;
            }
        }
    }
    return written;
}

}  // namespace luxel::ref
