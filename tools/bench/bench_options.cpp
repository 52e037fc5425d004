#include "bench_options.hpp"

#include <cmath>
#include <sstream>

#include "luxel/runtime/error.hpp"

namespace luxel::bench {
namespace {

std::vector<std::string> split(const std::string& text, char separator) {
    std::vector<std::string> parts;
    std::string part;
    std::istringstream stream(text);
    while (std::getline(stream, part, separator)) {
        parts.push_back(part);
    }
    if (!text.empty() && text.back() == separator) {
        parts.emplace_back();
    }
    return parts;
}

double number(const std::string& text, const std::string& what) {
    std::size_t used = 0;
    double value = 0.0;
    try {
        value = std::stod(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == 0 || used != text.size() || !std::isfinite(value)) {
        throw Error(what + ": '" + text + "' is not a number");
    }
    return value;
}

/// "AxB" with positive integers.
void check_pair(const std::string& value, const std::string& what) {
    const auto parts = split(value, 'x');
    if (parts.size() != 2) {
        throw Error(what + ": '" + value + "' is not AxB");
    }
    for (const std::string& p : parts) {
        const double v = number(p, what);
        if (v < 1.0 || v != std::floor(v)) {
            throw Error(what + ": '" + value + "' needs whole numbers >= 1");
        }
    }
}

}  // namespace

Sweep parse_sweep(const std::string& text) {
    const std::size_t equals = text.find('=');
    if (equals == std::string::npos || equals == 0 || equals + 1 >= text.size()) {
        throw Error("--sweep " + text + ": expected KNOB=V1,V2,...");
    }
    Sweep sweep{text.substr(0, equals), split(text.substr(equals + 1), ',')};
    const std::string what = "--sweep " + sweep.knob;
    for (const std::string& value : sweep.values) {
        if (sweep.knob == "photons" || sweep.knob == "caustics") {
            check_pair(value, what);
        } else if (sweep.knob == "budget") {
            if (!(number(value, what) > 0.0)) {
                throw Error(what + ": budgets must be > 0 ms");
            }
        } else if (sweep.knob == "aim_n" || sweep.knob == "rays" ||
                   sweep.knob == "texels_per_unit") {
            const double v = number(value, what);
            if (v < 1.0 || v != std::floor(v)) {
                throw Error(what + ": '" + value + "' is not a whole number >= 1");
            }
        } else if (sweep.knob == "backend") {
            if (value != "cpu" && value != "gpu" && value != "gpu-plane" && value != "gpu-turn") {
                throw Error(what + ": '" + value +
                            "' is not a gather backend (cpu, gpu, gpu-plane, gpu-turn)");
            }
        } else if (sweep.knob == "kernel") {
            if (value != "larsen" && value != "box" && value != "cone" && value != "world" &&
                value != "mip" && value != "footprints" && value != "layer" &&
                value != "layer-footprints" && value != "layer-mip") {
                throw Error(what + ": '" + value +
                            "' is not a caustic kernel (larsen, box, cone, world, mip, "
                            "footprints, layer)");
            }
        } else if (sweep.knob == "aa" || sweep.knob == "sky_edges") {
            if (value != "on" && value != "off") {
                throw Error(what + ": '" + value + "' is not on or off");
            }
        } else if (sweep.knob == "footprint_scale") {
            const double v = number(value, what);
            if (!(v > 0.0) || v > 100.0) {
                throw Error(what + ": '" + value + "' is not a scale in (0, 100]");
            }
        } else if (sweep.knob == "footprint_min") {
            const double v = number(value, what);
            if (!(v >= 1.0) || v > 64.0) {
                throw Error(what + ": '" + value + "' is not a number of pixels in [1, 64]");
            }
        } else if (sweep.knob == "lightmap") {
            if (value != "bilinear" && value != "bicubic") {
                throw Error(what + ": '" + value + "' is not bilinear or bicubic");
            }
        } else if (sweep.knob == "filter") {
            const double v = number(value, what);
            if (v < 0.0 || v > 16.0 || v != std::floor(v)) {
                throw Error(what + ": '" + value + "' is not a whole number of texels in 0..16");
            }
        } else if (sweep.knob == "caustic_refine") {
            const double v = number(value, what);
            if (v < 0.0 || v > 1e8 || v != std::floor(v)) {
                throw Error(what + ": '" + value +
                            "' is not a whole number of photons in 0..100,000,000");
            }
        } else if (sweep.knob == "refine") {
            const double v = number(value, what);
            if (v < 1.0 || v > 1024.0 || v != std::floor(v)) {
                throw Error(what + ": '" + value + "' is not a whole number of passes in 1..1024");
            }
        } else if (sweep.knob == "local" || sweep.knob == "exact" || sweep.knob == "contact" ||
                   sweep.knob == "stitch" || sweep.knob == "probes" || sweep.knob == "aim_power" ||
                   sweep.knob == "local_order" || sweep.knob == "stand_in" ||
                   sweep.knob == "unmapped") {
            if (value != "0" && value != "1") {
                throw Error(what + ": '" + value + "' is not 0 (off) or 1 (on)");
            }
        } else if (sweep.knob == "catch_up") {
            const double v = number(value, what);
            if (!(v >= 0.0 && v <= 1.0)) {
                throw Error(what + ": '" + value + "' is not a share of the budget in 0..1");
            }
        } else if (sweep.knob == "probe_spacing") {
            const double v = number(value, what);
            if (!(v >= 0.05 && v <= 100.0)) {
                throw Error(what + ": '" + value + "' is not a spacing in metres in 0.05..100");
            }
        } else if (sweep.knob == "probe_basis") {
            if (value != "oct" && value != "sh2") {
                throw Error(what + ": '" + value +
                            "' is not oct (octahedral irradiance maps) or sh2 (band-2 harmonics)");
            }
        } else if (sweep.knob == "change_blend") {
            const double v = number(value, what);
            if (!(v >= 0.0 && v <= 60.0)) {
                throw Error(what + ": '" + value + "' is not a number of seconds in 0..60");
            }
        } else if (sweep.knob == "keep") {
            const double v = number(value, what);
            if (!(v >= 0.0 && v <= 100.0)) {
                throw Error(what + ": '" + value +
                            "' is not a number of standard deviations in 0..100");
            }
        } else {
            throw Error("--sweep " + sweep.knob +
                        ": unknown knob (budget, photons, aim_n, rays, texels_per_unit, filter, "
                        "refine, local, change_blend, exact, contact, stitch, aim_power, "
                        "local_order, probes, unmapped, "
                        "probe_spacing, "
                        "probe_basis, keep, "
                        "caustics, caustic_refine, stand_in, catch_up, backend, "
                        "kernel, footprint_scale, footprint_min, "
                        "aa, lightmap, sky_edges)");
        }
    }
    return sweep;
}

Change parse_change(const std::string& text) {
    const std::size_t colon = text.rfind(':');
    if (colon == std::string::npos || colon == 0) {
        throw Error("--change " + text +
                    ": expected NODE:dx,dy,dz, NODE:turn=ax,ay,az,deg, NODE:off, NODE:on, auto or "
                    "none");
    }
    Change change;
    change.node = text.substr(0, colon);
    const std::string what = text.substr(colon + 1);
    if (what == "off" || what == "on") {
        change.kind = what == "off" ? Change::Kind::Off : Change::Kind::On;
        return change;
    }
    if (what.rfind("turn=", 0) == 0) {
        const auto parts = split(what.substr(5), ',');
        if (parts.size() != 4) {
            throw Error("--change " + text + ": a turn needs the axis and the angle, ax,ay,az,deg");
        }
        change.kind = Change::Kind::Turn;
        for (int i = 0; i < 3; ++i) {
            change.axis[i] =
                static_cast<float>(number(parts[static_cast<std::size_t>(i)], "--change"));
        }
        change.degrees = static_cast<float>(number(parts[3], "--change"));
        if (!(glm::length(change.axis) > 0.0f)) {
            throw Error("--change " + text + ": the turn's axis is zero");
        }
        change.axis = glm::normalize(change.axis);
        return change;
    }
    const auto parts = split(what, ',');
    if (parts.size() != 3) {
        throw Error("--change " + text + ": the offset needs three numbers dx,dy,dz");
    }
    for (int i = 0; i < 3; ++i) {
        change.offset[i] =
            static_cast<float>(number(parts[static_cast<std::size_t>(i)], "--change"));
    }
    return change;
}

std::vector<double> parse_budgets(const std::string& text) {
    std::vector<double> budgets;
    for (const std::string& part : split(text, ',')) {
        const double v = number(part, "--budgets");
        if (!(v > 0.0)) {
            throw Error("--budgets: " + part + " is not a budget > 0 ms");
        }
        budgets.push_back(v);
    }
    if (budgets.empty()) {
        throw Error("--budgets: need at least one budget");
    }
    return budgets;
}

void parse_image_size(const std::string& text, ImageSpec& image) {
    const auto parts = split(text, 'x');
    if (parts.size() != 2) {
        throw Error("--image: '" + text + "' is not WIDTHxHEIGHT (e.g. 160x120)");
    }
    int size[2] = {0, 0};
    for (std::size_t i = 0; i < 2; ++i) {
        const double v = number(parts[i], "--image " + text);
        // 4096: a reference frame of more pixels would take hours at any useful spp.
        if (v < 1.0 || v > 4096.0 || v != std::floor(v)) {
            throw Error("--image: '" + text + "' needs whole numbers of pixels in 1..4096");
        }
        size[i] = static_cast<int>(v);
    }
    image.width = size[0];
    image.height = size[1];
}

void validate(const Options& options) {
    if (options.frames < 1) {
        throw Error("--frames: need at least one frame");
    }
    if (options.checkpoint < 1) {
        throw Error("--checkpoint: need at least one frame between checkpoints");
    }
    if (!(options.dt > 0.0) || !std::isfinite(options.dt)) {
        throw Error("--dt: must be > 0 seconds");
    }
    if (!std::isfinite(options.time) || options.time < 0.0) {
        throw Error("--time: must be a time >= 0");
    }
    if (options.reference.spp < 1) {
        throw Error("--ref-spp: need at least one sample");
    }
    if (options.image.spp < 1) {
        throw Error("--image-spp: need at least one sample per pixel");
    }
    for (const Sweep& sweep : options.sweeps) {
        if ((sweep.knob == "kernel" || sweep.knob == "aa" || sweep.knob == "lightmap" ||
             sweep.knob == "sky_edges" || sweep.knob == "footprint_scale" ||
             sweep.knob == "footprint_min") &&
            !options.image.enabled) {
            throw Error("--sweep " + sweep.knob +
                        ": it only changes the image, which --no-image turns off");
        }
    }
}

}  // namespace luxel::bench
