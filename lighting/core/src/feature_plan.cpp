#include "luxel/lighting/core/feature_plan.hpp"

#include <algorithm>
#include <cstdint>
#include <utility>

namespace luxel::lighting {

std::string_view name(Pass pass) {
    switch (pass) {
        case Pass::PhotonTracing:
            return "photon_tracing";
        case Pass::SelectiveProbes:
            return "selective_probes";
        case Pass::Caustics:
            return "caustics";
        case Pass::Aim:
            return "aim";
        case Pass::IimGather:
            return "iim_gather";
        case Pass::Shadows:
            return "shadows";
        case Pass::Direct:
            return "direct";
        case Pass::Specular:
            return "specular";
        case Pass::CausticFilter:
            return "caustic_filter";
        case Pass::IrradianceProbes:
            return "irradiance_probes";
    }
    return "unknown";
}

namespace {

/// "1 light", "3 lights".
std::string count(std::uint32_t n, std::string_view singular, std::string_view plural) {
    return std::to_string(n) + " " + std::string(n == 1 ? singular : plural);
}

}  // namespace

FeaturePlan::FeaturePlan(const SceneCensus& census) : census_(census) {
    const SceneCensus& c = census_;
    auto set = [this](Pass pass, bool on, std::string why) {
        on_[static_cast<std::size_t>(pass)] = on;
        reasons_[static_cast<std::size_t>(pass)] = std::move(why);
    };

    const bool lit = c.lights_enabled > 0;
    const std::string no_light = c.lights_total == 0
                                     ? "no light in the scene: no lighting work"
                                     : "none of the " + count(c.lights_total, "light", "lights") +
                                           " is enabled: no lighting work";
    const bool surfaces = c.lightmapped_surfaces > 0;
    const bool generators = c.caustic_generators > 0;
    // Nothing can have changed the lighting: tracing and gathering would reproduce what the
    // maps already hold. Dynamic objects at rest are as good as static.
    const bool idle = c.converged && c.moving_objects == 0 && c.geometry_changes == 0;
    const std::string idle_reason =
        c.dynamic_objects == 0
            ? "static scene, converged: nothing to update"
            : "converged, " + count(c.dynamic_objects, "dynamic object", "dynamic objects") +
                  " at rest: nothing to update";
    std::string busy;
    if (c.moving_objects > 0) {
        busy = count(c.moving_objects, "object", "objects") + " moving";
    } else if (c.geometry_changes > 0) {
        busy = count(c.geometry_changes, "geometry edit", "geometry edits");
    } else {
        busy = "not converged (work pending)";
    }
    const std::string lights = count(c.lights_enabled, "light", "lights");
    const std::string surface_count = count(c.lightmapped_surfaces, "surface", "surfaces");

    // Global photons, AIM and IIM all live on light-mapped surfaces.
    auto surface_pass = [&](Pass pass, std::string_view what) {
        if (!lit && c.maps_pending && surfaces && pass != Pass::PhotonTracing) {
            set(pass, true,
                "no light is enabled, but the light maps still hold the light of lights switched "
                "off: clearing them");
        } else if (!lit) {
            set(pass, false, no_light);
        } else if (!surfaces) {
            set(pass, false, "no light-mapped surface: " + std::string(what));
        } else if (idle) {
            set(pass, false, idle_reason);
        } else {
            set(pass, true, lights + ", " + surface_count + "; " + busy);
        }
    };
    surface_pass(Pass::PhotonTracing, "global photons would have nowhere to be stored");
    surface_pass(Pass::Aim, "no irradiance map to rebuild");
    surface_pass(Pass::IimGather, "no texel to gather");

    // Probes find the groups that geometry changes invalidated; a light change invalidates its
    // own groups, so a scene whose geometry never changes needs no probes.
    if (!photon_tracing()) {
        set(Pass::SelectiveProbes, false, "photon tracing is off: " + reason(Pass::PhotonTracing));
    } else if (c.dynamic_objects == 0 && c.geometry_changes == 0) {
        set(Pass::SelectiveProbes, false,
            "no dynamic object or geometry edit: light changes invalidate their groups directly");
    } else {
        set(Pass::SelectiveProbes, true,
            count(c.dynamic_objects, "dynamic object", "dynamic objects") + ", " + busy);
    }

    const std::string generator_count =
        count(c.caustic_generators, "caustic generator", "caustic generators");
    if (!lit) {
        set(Pass::Caustics, false, no_light);
        set(Pass::CausticFilter, false, no_light);
    } else if (!generators) {
        set(Pass::Caustics, false, "no caustic generator: no caustic photons traced");
        set(Pass::CausticFilter, false, "no caustic generator: no caustic buffers or filter pass");
    } else {
        if (idle) {
            set(Pass::Caustics, false, idle_reason);
        } else {
            set(Pass::Caustics, true, generator_count + " x " + lights + "; " + busy);
        }
        // The caustics already traced are still drawn every frame.
        set(Pass::CausticFilter, true, generator_count + ": caustic buffers and filter");
    }

    // Irradiance probes light what has no light map from the AIM-lit scene. They stay while
    // the scene is idle (the renderer interpolates them every frame); their passes run only
    // while some probe wants one.
    const std::string receivers = count(c.unmapped_receivers, "receiver without a light map",
                                        "receivers without a light map");
    if (!lit) {
        set(Pass::IrradianceProbes, false, no_light);
    } else if (!surfaces) {
        set(Pass::IrradianceProbes, false,
            "no light-mapped surface: no lit scene for irradiance probes to gather");
    } else if (c.unmapped_receivers == 0) {
        set(Pass::IrradianceProbes, false,
            "every diffuse mesh has a light map: no receiver needs irradiance probes");
    } else {
        set(Pass::IrradianceProbes, true,
            receivers + (c.probes_pending ? "; probes gathering" : "; probes converged"));
    }

    if (!lit) {
        set(Pass::Shadows, false, no_light);
        set(Pass::Direct, false, no_light);
        set(Pass::Specular, false, no_light);
    } else {
        set(Pass::Shadows, true, lights + " cast shadows");
        set(Pass::Direct, true, lights + " light the scene directly");
        if (c.specular_materials == 0) {
            set(Pass::Specular, false, "no specular material: nothing reflects");
        } else {
            set(Pass::Specular, true,
                count(c.specular_materials, "specular material", "specular materials"));
        }
    }
}

std::string FeaturePlan::reason(Pass pass) const {
    return reasons_[static_cast<std::size_t>(pass)];
}

std::string FeaturePlan::describe() const {
    constexpr std::size_t kNameWidth = 18;
    std::string table = "pass              state  reason\n";
    for (std::size_t p = 0; p < kPassCount; ++p) {
        const std::string_view pass_name = name(static_cast<Pass>(p));
        std::string line(pass_name);
        line.resize(std::max(kNameWidth, pass_name.size() + 1), ' ');
        line += on_[p] ? "on     " : "off    ";
        line += reasons_[p];
        table += line;
        table += '\n';
    }
    return table;
}

std::vector<Pass> FeaturePlan::changed_from(const FeaturePlan& previous) const {
    std::vector<Pass> changed;
    for (std::size_t p = 0; p < kPassCount; ++p) {
        if (on_[p] != previous.on_[p]) {
            changed.push_back(static_cast<Pass>(p));
        }
    }
    return changed;
}

std::size_t FeaturePlan::active_count() const {
    std::size_t n = 0;
    for (const bool on : on_) {
        n += on ? 1 : 0;
    }
    return n;
}

}  // namespace luxel::lighting
