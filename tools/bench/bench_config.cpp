#include "bench_config.hpp"

#include <algorithm>
#include <sstream>

namespace luxel::bench {
namespace {

std::uint32_t whole(const std::string& text) {
    return static_cast<std::uint32_t>(std::stoul(text));
}

void pair(const std::string& text, std::uint32_t& a, std::uint32_t& b) {
    const std::size_t x = text.find('x');
    a = whole(text.substr(0, x));
    b = whole(text.substr(x + 1));
}

}  // namespace

lighting::LightingConfig BenchConfig::lighting() const {
    lighting::LightingConfig config;
    config.photons.selective.groups = groups;
    config.photons.selective.per_group = per_group;
    config.photons.caustics.photons_per_pair = caustic_photons;
    config.photons.caustics.slices = caustic_slices;
    config.photons.caustics.refinement_photons = caustic_refine;
    config.photons.caustics.stand_in = stand_in != 0;
    config.caustic_catch_up_share = catch_up;
    config.maps.density.nearest = aim_n;
    config.gather.rays_per_texel = rays;
    config.texels_per_gather_unit = texels_per_unit;
    config.maps.iim_filter_radius = static_cast<int>(filter);
    config.maps.refine_passes = refine;
    config.maps.local_passes = local != 0;
    config.maps.change_blend_seconds = change_blend;
    config.maps.change_test_sigmas = keep;
    config.photons.selective.exact_invalidation = exact != 0;
    config.maps.contact_texels = contact != 0;
    config.gather.unmapped_radiance = unmapped != 0;
    config.maps.stitch_seams = stitch != 0;
    config.maps.aim_keeps_power = aim_power != 0;
    config.maps.order_local_passes = local_order != 0;
    if (probes == 0) {
        config.probes.max_probes = 0;
    }
    config.probes.spacing = static_cast<float>(probe_spacing);
    config.probes.basis =
        probe_basis == "sh2" ? lighting::ProbeBasis::Sh2 : lighting::ProbeBasis::Octahedral;
    return config;
}

std::string BenchConfig::knobs() const {
    std::ostringstream out;
    out << "photons=" << groups << "x" << per_group << " aim_n=" << aim_n << " rays=" << rays
        << " texels_per_unit=" << texels_per_unit << " filter=" << filter << " refine=" << refine
        << " local=" << local << " change_blend=" << change_blend << " exact=" << exact
        << " contact=" << contact << " keep=" << keep << " caustics=" << caustic_photons << "x"
        << caustic_slices << " backend=" << backend << " kernel=" << kernel << " aa=" << aa;
    if (stitch != 1) {
        out << " stitch=" << stitch;  // appended only when off: earlier runs' keys stay valid
    }
    if (local_order != 1) {
        out << " local_order=" << local_order;
    }
    if (aim_power != 1) {
        out << " aim_power=" << aim_power;
    }
    if (probes != 1) {
        out << " probes=" << probes;
    }
    if (unmapped != 1) {
        out << " unmapped=" << unmapped;
    }
    if (probe_spacing != lighting::IrradianceProbeSettings{}.spacing) {
        out << " probe_spacing=" << probe_spacing;
    }
    if (probe_basis != "oct") {
        out << " probe_basis=" << probe_basis;
    }
    if (lightmap != "bilinear") {
        out << " lightmap=" << lightmap;
    }
    if (sky_edges != "on") {
        out << " sky_edges=" << sky_edges;
    }
    if (footprint_scale != lighting::CausticPassSettings{}.footprint_scale) {
        out << " footprint_scale=" << footprint_scale;
    }
    if (footprint_min != lighting::CausticPassSettings{}.footprint_min_pixels) {
        out << " footprint_min=" << footprint_min;
    }
    if (caustic_refine != lighting::CausticSettings{}.refinement_photons) {
        out << " caustic_refine=" << caustic_refine;
    }
    if (stand_in != 1) {
        out << " stand_in=" << stand_in;
    }
    if (catch_up != lighting::LightingConfig{}.caustic_catch_up_share) {
        out << " catch_up=" << catch_up;
    }
    return out.str();
}

std::vector<BenchConfig> make_configs(const Options& options) {
    std::vector<double> budgets = options.budgets;
    for (const Sweep& sweep : options.sweeps) {
        if (sweep.knob == "budget") {
            for (const std::string& v : sweep.values) {
                budgets.push_back(std::stod(v));
            }
        }
    }
    std::sort(budgets.begin(), budgets.end());
    budgets.erase(std::unique(budgets.begin(), budgets.end()), budgets.end());

    std::vector<BenchConfig> variants{BenchConfig{}};
    for (const Sweep& sweep : options.sweeps) {
        for (const std::string& value : sweep.values) {
            BenchConfig c;
            if (sweep.knob == "photons") {
                pair(value, c.groups, c.per_group);
            } else if (sweep.knob == "caustics") {
                pair(value, c.caustic_photons, c.caustic_slices);
            } else if (sweep.knob == "aim_n") {
                c.aim_n = whole(value);
            } else if (sweep.knob == "rays") {
                c.rays = whole(value);
            } else if (sweep.knob == "texels_per_unit") {
                c.texels_per_unit = whole(value);
            } else if (sweep.knob == "filter") {
                c.filter = whole(value);
            } else if (sweep.knob == "refine") {
                c.refine = whole(value);
            } else if (sweep.knob == "caustic_refine") {
                c.caustic_refine = whole(value);
            } else if (sweep.knob == "local") {
                c.local = whole(value);
            } else if (sweep.knob == "exact") {
                c.exact = whole(value);
            } else if (sweep.knob == "local_order") {
                c.local_order = whole(value);
            } else if (sweep.knob == "stand_in") {
                c.stand_in = whole(value);
            } else if (sweep.knob == "catch_up") {
                c.catch_up = std::stod(value);
            } else if (sweep.knob == "aim_power") {
                c.aim_power = whole(value);
            } else if (sweep.knob == "contact") {
                c.contact = whole(value);
            } else if (sweep.knob == "unmapped") {
                c.unmapped = whole(value);
            } else if (sweep.knob == "stitch") {
                c.stitch = whole(value);
            } else if (sweep.knob == "probes") {
                c.probes = whole(value);
            } else if (sweep.knob == "probe_spacing") {
                c.probe_spacing = std::stod(value);
            } else if (sweep.knob == "probe_basis") {
                c.probe_basis = value;
            } else if (sweep.knob == "change_blend") {
                c.change_blend = std::stod(value);
            } else if (sweep.knob == "keep") {
                c.keep = std::stod(value);
            } else if (sweep.knob == "backend") {
                c.backend = value;
            } else if (sweep.knob == "kernel") {
                c.kernel = value;
            } else if (sweep.knob == "aa") {
                c.aa = value;
            } else if (sweep.knob == "lightmap") {
                c.lightmap = value;
            } else if (sweep.knob == "sky_edges") {
                c.sky_edges = value;
            } else if (sweep.knob == "footprint_scale") {
                c.footprint_scale = std::stod(value);
                c.kernel = "footprints";  // the knob means nothing with another kernel
            } else if (sweep.knob == "footprint_min") {
                c.footprint_min = std::stod(value);
                c.kernel = "footprints";
            } else {
                continue;  // budget: handled above
            }
            if (c.knobs() == BenchConfig{}.knobs()) {
                continue;
            }
            c.method = sweep.knob + "=" + value;
            variants.push_back(c);
        }
    }
    std::vector<BenchConfig> configs;
    for (const BenchConfig& variant : variants) {
        for (double budget : budgets) {
            BenchConfig c = variant;
            c.budget_ms = budget;
            configs.push_back(c);
        }
    }
    return configs;
}

}  // namespace luxel::bench
