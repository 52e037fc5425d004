// luxel-frame-error: the error of a frame against a reference frame, over the whole frame and
// over regions of it, where a user would see a local failure that a whole-frame figure hides.
//   luxel-frame-error FRAME.exr REFERENCE.exr [--region X0,Y0,X1,Y1]... [--block N]
// Both are linear RGB EXRs of the same size (luxel-sandbox --exr, luxel-ref -o). Per region
// (pixels X0 <= x < X1, Y0 <= y < Y1, rows from the top): relRMSE over RGB (docs/METHOD.md
// §10.2's image error) and the ratio of the means. --block N first averages N x N pixel blocks
// in both frames, which lowers a path-traced reference's own noise by N where the error looked
// for is wider than a block (docs/RESULTS.md, "Contact"). --picture OUT.png writes what the
// numbers say as a picture: the frame, the reference and their difference side by side at one
// exposure (the reference's metered one, or --exposure), each pixel --zoom times, of the whole
// frame or of --crop X0,Y0,X1,Y1 (a corner worth a close look, the exposure still metered over
// the whole reference).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "luxel/lighting/reference/error_metrics.hpp"
#include "luxel/runtime/cli.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/runtime/image.hpp"
#include "luxel/runtime/tool_main.hpp"

namespace {

struct Region {
    int x0 = 0;
    int y0 = 0;
    int x1 = 0;
    int y1 = 0;
    std::string name;
};

/// `text` of the option `option` (--region, --crop).
Region parse_region(const std::string& text, const std::string& option = "--region") {
    Region r;
    char tail = 0;
    if (std::sscanf(text.c_str(), "%d,%d,%d,%d%c", &r.x0, &r.y0, &r.x1, &r.y1, &tail) != 4) {
        throw luxel::UsageError(option + " " + text + ": not X0,Y0,X1,Y1 (whole pixels)");
    }
    r.name = "region " + text;
    return r;
}

struct Figures {
    double relative_rmse = 0.0;
    double mean_ratio = 0.0;
    long blocks = 0;
    /// Mean linear RGB of the frame and of the reference over the region: a colour shift
    /// (a wall's tint missing) shows here before it shows in one number.
    glm::dvec3 frame_mean{0.0};
    glm::dvec3 reference_mean{0.0};
};

/// The N x N block means of `image` over `r` (a block partly outside `r` is left out), as an
/// image of its own.
luxel::Image blocks_of(const luxel::Image& image, const Region& r, int block) {
    luxel::Image out((r.x1 - r.x0) / block, (r.y1 - r.y0) / block);
    const auto area = static_cast<float>(block * block);
    for (int by = 0; by < out.height; ++by) {
        for (int bx = 0; bx < out.width; ++bx) {
            glm::vec4 sum(0.0f);
            for (int dy = 0; dy < block; ++dy) {
                for (int dx = 0; dx < block; ++dx) {
                    sum += image.pixel(r.x0 + bx * block + dx, r.y0 + by * block + dy);
                }
            }
            out.set_pixel(bx, by, sum / area);
        }
    }
    return out;
}

/// relRMSE (the image error of docs/METHOD.md §10.2, the same function luxel-bench uses) and the
/// ratio of means over `r`, on N x N blocks. A black reference with a non-black frame reads
/// infinity.
Figures compare(const luxel::Image& frame, const luxel::Image& reference, const Region& r,
                int block) {
    const luxel::Image a = blocks_of(frame, r, block);
    const luxel::Image b = blocks_of(reference, r, block);
    Figures out;
    out.relative_rmse = luxel::lighting::reference::image_relative_rmse(a, b);
    out.blocks = static_cast<long>(a.width) * a.height;
    for (std::size_t i = 0; i < a.rgba.size(); i += 4) {
        for (std::size_t c = 0; c < 3; ++c) {
            out.frame_mean[static_cast<int>(c)] += a.rgba[i + c];
            out.reference_mean[static_cast<int>(c)] += b.rgba[i + c];
        }
    }
    const double frame_sum = out.frame_mean.x + out.frame_mean.y + out.frame_mean.z;
    const double reference_sum = out.reference_mean.x + out.reference_mean.y + out.reference_mean.z;
    if (out.blocks > 0) {
        out.frame_mean /= static_cast<double>(out.blocks);
        out.reference_mean /= static_cast<double>(out.blocks);
    }
    const double inf = std::numeric_limits<double>::infinity();
    out.mean_ratio =
        reference_sum > 0.0 ? frame_sum / reference_sum : (frame_sum > 0.0 ? inf : 1.0);
    return out;
}

/// frame | reference | difference over `crop`, `zoom` x `zoom` screen pixels a pixel, 4 pixels
/// apart. The
/// first two at `exposure`; the difference as a signed map at the same exposure (red where the
/// frame is brighter, blue where it is darker, in luminance), so a patch plainly wrong shows
/// at once where the numbers only say "somewhere".
luxel::Image side_by_side(const luxel::Image& frame, const luxel::Image& reference,
                          const Region& crop, int zoom, float exposure) {
    constexpr int kGap = 4;
    const int w = (crop.x1 - crop.x0) * zoom;
    const int h = (crop.y1 - crop.y0) * zoom;
    luxel::Image out(3 * w + 2 * kGap, h, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const glm::vec4 a = frame.pixel(crop.x0 + x / zoom, crop.y0 + y / zoom);
            const glm::vec4 b = reference.pixel(crop.x0 + x / zoom, crop.y0 + y / zoom);
            const auto d = static_cast<float>(luxel::luminance(glm::dvec3(glm::vec3(a))) -
                                              luxel::luminance(glm::dvec3(glm::vec3(b))));
            out.set_pixel(x, y, glm::vec4(glm::vec3(a) * exposure, 1.0f));
            out.set_pixel(w + kGap + x, y, glm::vec4(glm::vec3(b) * exposure, 1.0f));
            out.set_pixel(
                2 * (w + kGap) + x, y,
                glm::vec4(std::max(d, 0.0f), 0.0f, std::max(-d, 0.0f), 1.0f) * (4.0f * exposure));
        }
    }
    return out;
}

void check_finite(const luxel::Image& image, const std::string& file) {
    for (std::size_t i = 0; i < image.rgba.size(); ++i) {
        if (!std::isfinite(image.rgba[i])) {
            const auto pixel = static_cast<long>(i / 4);
            throw luxel::Error(file + ": pixel " + std::to_string(pixel % image.width) + ", " +
                               std::to_string(pixel / image.width) + " is not finite");
        }
    }
}

int run(int argc, char** argv) {
    CLI::App app{
        "The error of a linear EXR frame against a reference frame of the same size: relRMSE "
        "over RGB and the ratio of means, over the whole frame and over regions of it."};
    std::string frame_file;
    std::string reference_file;
    std::vector<std::string> regions_text;
    int block = 1;
    app.add_option("frame", frame_file, "the frame (EXR)")->required();
    app.add_option("reference", reference_file, "the reference frame (EXR)")->required();
    app.add_option("--region", regions_text,
                   "X0,Y0,X1,Y1: pixels X0 <= x < X1, Y0 <= y < Y1, rows from the top "
                   "(repeatable)");
    app.add_option("--block", block, "average N x N pixel blocks before comparing")
        ->check(CLI::Range(1, 4096))
        ->capture_default_str();
    std::string picture_file;
    int zoom = 1;
    float exposure = 0.0f;
    app.add_option("--picture", picture_file,
                   "also write frame | reference | difference (red: the frame brighter, blue: "
                   "darker, 4x the exposure) side by side as a PNG");
    std::string crop_text;
    app.add_option("--crop", crop_text,
                   "X0,Y0,X1,Y1: the picture shows these pixels only (the exposure is still "
                   "metered over the whole reference)");
    app.add_option("--zoom", zoom, "screen pixels per frame pixel in the picture")
        ->check(CLI::Range(1, 16))
        ->capture_default_str();
    app.add_option("--exposure", exposure,
                   "the picture's linear exposure (0: the reference's metered exposure)")
        ->check(CLI::Range(0.0f, 1e9f))
        ->capture_default_str();
    if (!luxel::cli::parse(app, argc, argv)) {
        return 0;
    }
    std::vector<Region> regions;
    for (const std::string& text : regions_text) {
        regions.push_back(parse_region(text));
    }
    const luxel::Image frame = luxel::read_exr(frame_file);
    const luxel::Image reference = luxel::read_exr(reference_file);
    if (frame.width != reference.width || frame.height != reference.height) {
        throw luxel::Error(reference_file + ": " + std::to_string(reference.width) + "x" +
                           std::to_string(reference.height) + ", the frame " + frame_file + " is " +
                           std::to_string(frame.width) + "x" + std::to_string(frame.height));
    }
    check_finite(frame, frame_file);
    check_finite(reference, reference_file);
    Region whole{0, 0, frame.width, frame.height, "whole frame"};
    const auto check_inside = [&](const Region& r, int smallest) {
        if (r.x0 < 0 || r.y0 < 0 || r.x1 > frame.width || r.y1 > frame.height ||
            r.x1 - r.x0 < smallest || r.y1 - r.y0 < smallest) {
            throw luxel::UsageError(r.name + ": not inside the " + std::to_string(frame.width) +
                                    "x" + std::to_string(frame.height) +
                                    " frame, or smaller than one block");
        }
    };
    Region crop = whole;
    if (!crop_text.empty()) {
        crop = parse_region(crop_text, "--crop");
        crop.name = "--crop " + crop_text;
        check_inside(crop, 1);
    }
    regions.insert(regions.begin(), whole);
    for (const Region& r : regions) {
        check_inside(r, block);
        const Figures f = compare(frame, reference, r, block);
        char line[512];
        std::snprintf(line, sizeof(line),
                      "%s: relRMSE %.2f%%, mean ratio %.4f (%ld blocks of %dx%d); mean RGB "
                      "%.4g %.4g %.4g against %.4g %.4g %.4g",
                      r.name.c_str(), 100.0 * f.relative_rmse, f.mean_ratio, f.blocks, block, block,
                      f.frame_mean.x, f.frame_mean.y, f.frame_mean.z, f.reference_mean.x,
                      f.reference_mean.y, f.reference_mean.z);
        std::cout << line << "\n";
    }
    if (!picture_file.empty()) {
        // Checked before the picture is allocated: 3 panels of (W zoom) x (H zoom) RGBA floats.
        constexpr double kMaxPicturePixels = 64.0 * 1024.0 * 1024.0;
        if (3.0 * (crop.x1 - crop.x0) * zoom * (crop.y1 - crop.y0) * zoom > kMaxPicturePixels) {
            throw luxel::UsageError("--zoom " + std::to_string(zoom) + ": the picture of a " +
                                    std::to_string(crop.x1 - crop.x0) + "x" +
                                    std::to_string(crop.y1 - crop.y0) +
                                    " frame would exceed 64 Mpixels; use a smaller zoom");
        }
        const float shown = exposure > 0.0f ? exposure : luxel::metered_exposure(reference);
        luxel::write_png(picture_file, side_by_side(frame, reference, crop, zoom, shown),
                         luxel::ToneMapSettings{.exposure = 1.0f});
        std::cout << "picture: " << picture_file << " (exposure " << shown << ")\n";
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return luxel::run_tool("luxel-frame-error", run, argc, argv);
}
