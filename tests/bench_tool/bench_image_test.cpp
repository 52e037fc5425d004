// luxel-bench's image error and its GPU-backend / caustic-kernel knobs: the image columns are
// numbers in CSV and JSON when the image is on and say "not_measured" with --no-image, a bad
// --image is named, and a sweep over backend=cpu,gpu runs both gather backends.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "bench_outputs.hpp"
#include "luxel/runtime/image.hpp"
#include "temp_dir.hpp"
#include "test_paths.hpp"

namespace {

using luxel::testing::cell_number;
using luxel::testing::column_index;
using luxel::testing::CommandResult;
using luxel::testing::count;
using luxel::testing::CsvRows;
using luxel::testing::luxel_bench;
using luxel::testing::quoted;
using luxel::testing::read_csv;
using luxel::testing::read_text;

/// The columns the image adds to runs.csv (and to every run of results.json).
const std::vector<std::string> kImageColumns{"image_relrmse", "image_relrmse_net",
                                             "ref_se_image",  "image_after",
                                             "frame_gpu_ms",  "caustic_gpu_ms"};

nlohmann::json read_json(const std::filesystem::path& path) {
    std::ifstream in(path);
    return nlohmann::json::parse(in);
}

TEST(BenchImage, BadImageValuesAreExplained) {
    for (const char* bad : {"160by120", "0x120", "160x", "160x120x2", "5000x10"}) {
        const CommandResult run =
            luxel_bench(std::string("--level cornell --frames 1 --image ") + bad);
        EXPECT_NE(run.exit_code, 0) << bad;
        EXPECT_NE(run.output.find("--image"), std::string::npos) << bad << ": " << run.output;
        EXPECT_NE(run.output.find(bad), std::string::npos) << bad << ": " << run.output;
    }
    CommandResult run = luxel_bench("--level cornell --frames 1 --image 32x24 --no-image");
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.output.find("--no-image"), std::string::npos) << run.output;
    run = luxel_bench("--level cornell --frames 1 --image-spp 0");
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.output.find("--image-spp"), std::string::npos) << run.output;
    run = luxel_bench("--level cornell --frames 1 --sweep backend=cuda");
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.output.find("cuda"), std::string::npos) << run.output;
    run = luxel_bench("--level cornell --frames 1 --sweep kernel=gauss");
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.output.find("gauss"), std::string::npos) << run.output;
    // The kernel only changes the frame: sweeping it without one would be rows of nothing.
    run = luxel_bench("--level cornell --frames 1 --no-image --sweep kernel=box");
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.output.find("--no-image"), std::string::npos) << run.output;
    // The photon footprints' two knobs: named when out of range, and frame-only as the kernel.
    run = luxel_bench("--level cornell --frames 1 --sweep footprint_min=0.5");
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.output.find("footprint_min"), std::string::npos) << run.output;
    run = luxel_bench("--level cornell --frames 1 --sweep footprint_scale=0");
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.output.find("footprint_scale"), std::string::npos) << run.output;
    run = luxel_bench("--level cornell --frames 1 --no-image --sweep footprint_scale=1");
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.output.find("--no-image"), std::string::npos) << run.output;
}

TEST(BenchImage, TheImageErrorIsAFiniteNumberInCsvAndJson) {
    luxel::testing::TempDir dir("luxel-bench-image");
    const std::filesystem::path out = dir / "out";
    // 4 frames from cold gather no indirect light yet: the frame has its direct light,
    // caustics and specular, and no indirect. A 64-spp reference of 32 x 24 pixels takes a
    // fraction of a second and has a relative standard error near 0.17.
    const CommandResult run = luxel_bench(
        "--level cornell --budgets 8 --frames 4 --after 2 --checkpoint 2 --ref-photons 100000 "
        "--ref-caustic-photons 50000 --ref-spp 1 --image 32x24 --image-spp 64 "
        "--sweep kernel=world --threads 2 --out " +
        quoted(out));
    ASSERT_EQ(run.exit_code, 0) << run.output;

    const CsvRows rows = read_csv(out / "runs.csv");
    ASSERT_EQ(rows.size(), 3u);  // header, paper, kernel=world
    for (const std::string& column : kImageColumns) {
        ASSERT_LT(column_index(rows, column), rows[0].size()) << column;
    }
    const auto value = [&](std::size_t row, const std::string& column) {
        return cell_number(rows[row].at(column_index(rows, column)));
    };
    const std::filesystem::path results = out / "results.json";
    const nlohmann::json json = read_json(results);
    ASSERT_EQ(json["runs"].size(), 2u);
    EXPECT_TRUE(json["image"]["measured"].get<bool>());
    EXPECT_EQ(json["image"]["width"], 32);
    for (std::size_t r = 1; r < rows.size(); ++r) {
        for (const std::string& column : kImageColumns) {
            EXPECT_TRUE(std::isfinite(value(r, column))) << column << " row " << r;
            const std::string cell = json["runs"][r - 1][column].get<std::string>();
            EXPECT_TRUE(std::isfinite(cell_number(cell))) << column << " in JSON: " << cell;
        }
        const double image = value(r, "image_relrmse");
        const double se = value(r, "ref_se_image");
        const double net = value(r, "image_relrmse_net");
        std::printf("[ figures  ] %s: image relRMSE %.4f, net %.4f, reference SE %.4f\n",
                    rows[r][1].c_str(), image, net, se);
        // An all-black frame scores exactly 1, a frame 1.5x too bright 0.5. This one lacks
        // only the indirect light (a fraction of cornell's radiance; 0.27 measured, most of it
        // the reference's own noise): 0.5 passes it and fails a black, unlit or badly exposed
        // frame.
        EXPECT_GT(image, 0.0) << rows[r][1];
        EXPECT_LT(image, 0.5) << rows[r][1];
        // The net figure follows from the two others; the CSV rounds to 4 and 5 decimals.
        const double expected = std::sqrt(std::max(0.0, (image * image - se * se) / (1 - se * se)));
        EXPECT_NEAR(net, expected, 2e-4) << rows[r][1];
        EXPECT_LE(net, image + 1e-4) << rows[r][1];
    }
    EXPECT_EQ(rows[2][column_index(rows, "kernel")], "world");

    // Checkpoints carry the image error too (rendered at every checkpoint).
    const CsvRows checkpoints = read_csv(out / "checkpoints.csv");
    const std::size_t image_column = column_index(checkpoints, "image_relrmse");
    ASSERT_LT(image_column, checkpoints[0].size());
    for (std::size_t r = 1; r < checkpoints.size(); ++r) {
        EXPECT_TRUE(std::isfinite(cell_number(checkpoints[r].at(image_column)))) << "row " << r;
    }

    // Real time | 4 black pixels | reference, one picture per run and phase.
    for (const char* png : {"frames/paper_8ms_static.png", "frames/paper_8ms_after.png",
                            "frames/kernel=world_8ms_static.png"}) {
        const luxel::Image8 image = luxel::read_png(out / png);
        EXPECT_EQ(image.width, 2 * 32 + 4) << png;
        EXPECT_EQ(image.height, 24) << png;
    }
    EXPECT_EQ(count(read_text(out / "summary.md"), "not measured"), 0u);
}

// --camera places both compared frames (real time and reference) where luxel-ref's --camera
// would: from the middle of cornell looking at its red wall, both halves of the side-by-side
// picture are red.
TEST(BenchImage, TheCameraFlagPlacesBothFrames) {
    luxel::testing::TempDir dir("luxel-bench-camera");
    const std::filesystem::path out = dir / "out";
    const CommandResult run = luxel_bench(
        "--level cornell --budgets 8 --frames 2 --after 1 --checkpoint 1 --change none "
        "--ref-photons 100000 --ref-caustic-photons 50000 --ref-spp 1 --image 32x24 "
        "--image-spp 16 --threads 2 --camera 0,1,0:-1,1,0:40 --out " +
        quoted(out));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_NE(read_text(out / "summary.md").find("the --camera view"), std::string::npos);
    const luxel::Image8 image = luxel::read_png(out / "frames/paper_8ms_static.png");
    ASSERT_EQ(image.width, 2 * 32 + 4);
    for (const int x0 : {0, 32 + 4}) {  // real time | 4 black pixels | reference
        double red = 0.0;
        double green = 0.0;
        for (int y = 0; y < image.height; ++y) {
            for (int x = x0; x < x0 + 32; ++x) {
                red += image.at(x, y, 0);
                green += image.at(x, y, 1);
            }
        }
        EXPECT_GT(red, 2.0 * green) << "the half at x " << x0 << " should show the red wall";
    }
}

TEST(BenchImage, TheCausticTermIsMeasuredAtPixelResolution) {
    CommandResult run = luxel_bench("--level cornell --frames 1 --no-image --caustic-pixels");
    EXPECT_EQ(run.exit_code, 2) << run.output;
    EXPECT_NE(run.output.find("--caustic-pixels"), std::string::npos) << run.output;

    // Cornell's glass sphere throws its caustic on the floor the camera sees. An unlimited
    // budget: at 8 ms the caustic photons were still untraced after 16 frames when the machine
    // was busy (the sanitized build beside another test), since budgets run on the wall clock.
    luxel::testing::TempDir dir("luxel-bench-caustic-pixels");
    const std::filesystem::path out = dir / "out";
    run = luxel_bench(
        "--level cornell --budgets 100000 --frames 16 --after 1 --checkpoint 8 --change none "
        "--ref-photons 100000 --ref-caustic-photons 2000000 --ref-spp 1 --image 32x24 "
        "--image-spp 4 --threads 2 --caustic-pixels --out " +
        quoted(out));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_NE(run.output.find("caustic at pixel resolution"), std::string::npos) << run.output;
    const nlohmann::json json = read_json(out / "results.json");
    const auto& result = json["runs"][0];
    ASSERT_TRUE(result.contains("caustic_pixels_relrmse")) << result.dump();
    const double error = result["caustic_pixels_relrmse"].get<double>();
    EXPECT_TRUE(std::isfinite(error));
    EXPECT_GT(error, 0.0);
    EXPECT_LT(error, 2.0) << "the real-time caustic lands where the reference's does";
    EXPECT_GT(result["ref_se_caustic_pixels"].get<double>(), 0.0);
    const luxel::Image caustics =
        luxel::read_exr(out / "frames/paper_100000ms_static_caustics.exr");
    double sum = 0.0;
    for (int y = 0; y < caustics.height; ++y) {
        for (int x = 0; x < caustics.width; ++x) {
            sum += caustics.pixel(x, y).g;
        }
    }
    EXPECT_GT(sum, 0.0) << "the caustic term alone is drawn";
    EXPECT_TRUE(std::filesystem::exists(out / "frames/paper_100000ms_static_caustics.png"));
}

TEST(BenchImage, PixelsWithoutALightMapAreMeasuredOnTheirOwn) {
    // The skinned figure has no light map: the irradiance probes light it, and the error over
    // its pixels is reported apart from the frame's. Without probes (probes=0) the figure
    // lacks all its indirect light, and that error is larger.
    luxel::testing::TempDir dir("luxel-bench-unmapped");
    const std::filesystem::path out = dir / "out";
    const std::filesystem::path level =
        luxel::testing::source_dir() / "assets/levels/prepared/skinned-figure.glb";
    const CommandResult run = luxel_bench(
        "--level " + quoted(level) +
        " --budgets 100000 --frames 20 --checkpoint 20 --change none --ref-photons 200000 "
        "--ref-caustic-photons 1000 --ref-spp 1 --image 48x36 --image-spp 64 --threads 2 "
        "--camera 0.9,1.5,2.4:-0.5,0.9,0.2:40 --sweep probes=0 --out " +
        quoted(out));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const CsvRows rows = read_csv(out / "runs.csv");
    ASSERT_EQ(rows.size(), 3u);  // header, paper, probes=0
    const auto value = [&](std::size_t row, const std::string& column) {
        return cell_number(rows[row].at(column_index(rows, column)));
    };
    for (std::size_t r = 1; r < rows.size(); ++r) {
        EXPECT_GT(value(r, "unmapped_pixels"), 100.0) << rows[r][1];
        EXPECT_GT(value(r, "image_unmapped_relrmse"), 0.0) << rows[r][1];
        EXPECT_LT(value(r, "image_unmapped_relrmse"), 1.0) << rows[r][1];
        // Their interior (5x5 neighbourhoods without a light map): fewer pixels, still some.
        EXPECT_GT(value(r, "unmapped_interior_pixels"), 10.0) << rows[r][1];
        EXPECT_LT(value(r, "unmapped_interior_pixels"), value(r, "unmapped_pixels")) << rows[r][1];
        EXPECT_GT(value(r, "image_unmapped_interior_relrmse"), 0.0) << rows[r][1];
        std::printf(
            "[ figures  ] %s: pixels without a light map %.0f, their relRMSE %.4f; interior %.0f, "
            "%.4f\n",
            rows[r][1].c_str(), value(r, "unmapped_pixels"), value(r, "image_unmapped_relrmse"),
            value(r, "unmapped_interior_pixels"), value(r, "image_unmapped_interior_relrmse"));
    }
    EXPECT_LT(value(1, "image_unmapped_relrmse"), value(2, "image_unmapped_relrmse"));
}

// --no-light-map NODE: cornell's cube loses its light map, so its pixels join those measured
// apart (the glass sphere's) and the light-map reference leaves its texels out; a node that is
// not there, or has no light map, is named.
TEST(BenchImage, ANodeLeftWithoutALightMapIsMeasuredWithTheUnmappedPixels) {
    luxel::testing::TempDir dir("luxel-bench-no-light-map");
    const std::string tiny =
        "--level cornell --budgets 100000 --frames 4 --checkpoint 4 --change none "
        "--ref-photons 100000 --ref-caustic-photons 1000 --ref-spp 1 --image 48x36 "
        "--image-spp 4 --threads 2 --out ";
    const CommandResult mapped = luxel_bench(tiny + quoted(dir / "mapped"));
    ASSERT_EQ(mapped.exit_code, 0) << mapped.output;
    const CommandResult unmapped =
        luxel_bench(tiny + quoted(dir / "unmapped") + " --no-light-map 'moving cube'");
    ASSERT_EQ(unmapped.exit_code, 0) << unmapped.output;
    const auto pixels = [](const std::filesystem::path& out) {
        const CsvRows rows = read_csv(out / "runs.csv");
        return cell_number(rows.at(1).at(column_index(rows, "unmapped_pixels")));
    };
    const double sphere = pixels(dir / "mapped");
    const double sphere_and_cube = pixels(dir / "unmapped");
    std::printf("[ figures  ] pixels without a light map: %.0f, with the cube's %.0f\n", sphere,
                sphere_and_cube);
    EXPECT_GT(sphere_and_cube, sphere + 20.0);
    // The light-map reference leaves the cube's texels out (its key counts them).
    const auto texels = [](const std::string& output) {
        const std::size_t at = output.find("texels=");
        return at == std::string::npos ? -1L : std::stol(output.substr(at + 7));
    };
    EXPECT_GT(texels(unmapped.output), 0L) << unmapped.output;
    EXPECT_LT(texels(unmapped.output), texels(mapped.output));

    CommandResult bad = luxel_bench(tiny + quoted(dir / "bad") + " --no-light-map 'no such node'");
    EXPECT_EQ(bad.exit_code, 1) << bad.output;
    EXPECT_NE(bad.output.find("--no-light-map no such node"), std::string::npos) << bad.output;
    EXPECT_NE(bad.output.find("has no node of that name"), std::string::npos) << bad.output;
    bad = luxel_bench(tiny + quoted(dir / "bad") + " --no-light-map camera");
    EXPECT_EQ(bad.exit_code, 1) << bad.output;
    EXPECT_NE(bad.output.find("has no light map to leave out"), std::string::npos) << bad.output;
}

TEST(BenchImage, ATexturedLevelBlenderWroteMatchesTheReferenceWithinEightPercent) {
    // Issue 21's textured goal on the level Blender's exporter wrote (emissive-sign.py: an
    // emissive texture on a sign, a checker floor), seen from above the floor: luxel-ref reads
    // both textures at every hit and box-filters each pixel. Measured 6.05% here (the textures'
    // level-of-detail bias of -0.5); without the bias the trilinear blur at the sign's edges
    // read 8.27%.
    luxel::testing::TempDir dir("luxel-bench-textured");
    const std::filesystem::path out = dir / "out";
    const std::filesystem::path level =
        luxel::testing::source_dir() / "assets/levels/prepared/emissive-sign.glb";
    const CommandResult run = luxel_bench(
        "--level " + quoted(level) +
        " --budgets 100000 --frames 30 --checkpoint 30 --change none --ref-photons 1000000 "
        "--ref-caustic-photons 1000 --ref-spp 1 --image 160x90 --image-spp 64 --threads 2 "
        "--camera 0,1.2,1.5:0,0,-0.5:70 --out " +
        quoted(out));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const CsvRows rows = read_csv(out / "runs.csv");
    ASSERT_EQ(rows.size(), 2u);
    const double image = cell_number(rows[1].at(column_index(rows, "image_relrmse")));
    std::printf("[ figures  ] emissive-sign, the floor's view: image relRMSE %.4f\n", image);
    EXPECT_GT(image, 0.0);
    EXPECT_LT(image, 0.08);
}

/// The mean RGB of `image` over pixels [x0, x1) x [y0, y1).
glm::dvec3 region_mean(const luxel::Image& image, int x0, int y0, int x1, int y1) {
    glm::dvec3 sum(0.0);
    for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
            sum += glm::dvec3(glm::vec3(image.pixel(x, y)));
        }
    }
    return sum / static_cast<double>((x1 - x0) * (y1 - y0));
}

TEST(BenchImage, GlassBlenderWroteMatchesTheReferenceWithinFivePercent) {
    // Issue 21's transmission goal on the level Blender's exporter wrote (tinted-glass.py: an
    // amber glass cube with KHR_materials_volume standing on the floor, a blue single-quad
    // pane), from its own camera: the glass pixels' mean within 5% of luxel-ref's, and the
    // colour through the pane within 5% per channel. Measured 1.041 (cube) and 1.011 (pane;
    // 1.008 1.011 1.012 per channel) here; the cube read 0.839 before the gather, the
    // reference and the frame scaled radiance across a closed solid's faces and absorbed inside
    // it on the way to the floor under it (docs/RESULTS.md, "Tinted and absorbing glass").
    luxel::testing::TempDir dir("luxel-bench-glass");
    const std::filesystem::path out = dir / "out";
    const std::filesystem::path level =
        luxel::testing::source_dir() / "assets/levels/prepared/tinted-glass.glb";
    // 120 frames: the light maps' refinement passes fade in over the first hundred.
    const CommandResult run = luxel_bench(
        "--level " + quoted(level) +
        " --budgets 100000 --frames 120 --checkpoint 120 --change none --ref-photons 1000000 "
        "--ref-caustic-photons 1000000 --ref-spp 1 --image 160x120 --image-spp 256 --threads 2 "
        "--out " +
        quoted(out));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const luxel::Image frame = luxel::read_exr(out / "frames/paper_100000ms_static.exr");
    std::filesystem::path reference_path;
    for (const auto& entry : std::filesystem::directory_iterator(out / "cache")) {
        const std::string name = entry.path().filename().string();
        if (name.size() > 10 && name.ends_with(".frame.exr")) {
            reference_path = entry.path();
        }
    }
    ASSERT_FALSE(reference_path.empty()) << "no reference frame in " << (out / "cache");
    const luxel::Image reference = luxel::read_exr(reference_path);
    ASSERT_EQ(frame.width, 160);
    ASSERT_EQ(reference.width, 160);
    // The cube's and the pane's pixels at the level's camera (160 x 120).
    const glm::dvec3 cube = region_mean(frame, 28, 56, 60, 88);
    const glm::dvec3 cube_reference = region_mean(reference, 28, 56, 60, 88);
    const glm::dvec3 pane = region_mean(frame, 100, 32, 138, 64);
    const glm::dvec3 pane_reference = region_mean(reference, 100, 32, 138, 64);
    const auto sum = [](const glm::dvec3& v) { return v.x + v.y + v.z; };
    std::printf(
        "[ figures  ] tinted-glass, frame / reference: cube %.4f (%.3f %.3f %.3f), pane "
        "%.4f (%.3f %.3f %.3f)\n",
        sum(cube) / sum(cube_reference), cube.x / cube_reference.x, cube.y / cube_reference.y,
        cube.z / cube_reference.z, sum(pane) / sum(pane_reference), pane.x / pane_reference.x,
        pane.y / pane_reference.y, pane.z / pane_reference.z);
    EXPECT_NEAR(sum(cube) / sum(cube_reference), 1.0, 0.05);
    EXPECT_NEAR(sum(pane) / sum(pane_reference), 1.0, 0.05);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(pane[c] / pane_reference[c], 1.0, 0.05) << "channel " << c;
    }
}

TEST(BenchImage, NoImageMarksTheColumnsNotMeasuredAndMakesNoContext) {
    luxel::testing::TempDir dir("luxel-bench-no-image");
    const std::filesystem::path out = dir / "out";
    const CommandResult run = luxel_bench(
        "--level cornell --budgets 8 --frames 2 --after 1 --checkpoint 2 --ref-photons 100000 "
        "--ref-caustic-photons 50000 --ref-spp 1 --no-image --threads 2 --out " +
        quoted(out));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    // The bench logs the GL renderer when it makes a context; without the image it has none.
    EXPECT_EQ(count(run.output, "luxel-bench: GL "), 0u) << run.output;
    EXPECT_EQ(count(run.output, "reference frame"), 0u) << run.output;

    const CsvRows rows = read_csv(out / "runs.csv");
    ASSERT_EQ(rows.size(), 2u);
    const nlohmann::json json = read_json(out / "results.json");
    EXPECT_FALSE(json["image"]["measured"].get<bool>());
    for (const std::string& column : kImageColumns) {
        const std::size_t c = column_index(rows, column);
        ASSERT_LT(c, rows[0].size()) << column;
        EXPECT_EQ(rows[1][c], "not_measured") << column;
        EXPECT_EQ(json["runs"][0][column], "not_measured") << column;
    }
    EXPECT_FALSE(std::filesystem::exists(out / "frames"));
    EXPECT_FALSE(std::filesystem::exists(out / "image_vs_ms.png"));
    const std::string summary = read_text(out / "summary.md");
    EXPECT_NE(summary.find("Image error: **not measured**"), std::string::npos) << summary;
}

TEST(BenchImage, ASweepOverBothGatherBackendsRunsBoth) {
    luxel::testing::TempDir dir("luxel-bench-backend");
    const std::filesystem::path out = dir / "out";
    // A budget no frame can reach, so the scheduler's queues and not the machine's speed decide
    // how much is gathered (both backends gather their first units by frame 4). At 1000 ms a
    // new machine's first GPU gathers on llvmpipe, with the other core busy, gathered nothing in
    // 6 frames (found by scripts/fresh-machine.sh).
    const CommandResult run = luxel_bench(
        "--level cornell --budgets 1e9 --frames 6 --checkpoint 2 --change none "
        "--ref-photons 100000 --ref-caustic-photons 50000 --ref-spp 1 --no-image "
        "--sweep backend=cpu,gpu --threads 2 --out " +
        quoted(out));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    // backend=gpu needs the GL context even without the image.
    EXPECT_EQ(count(run.output, "luxel-bench: GL "), 1u) << run.output;

    const CsvRows rows = read_csv(out / "runs.csv");
    ASSERT_EQ(rows.size(), 3u);  // header, paper (= backend=cpu, not repeated), backend=gpu
    const std::size_t backend = column_index(rows, "backend");
    const std::size_t indirect = column_index(rows, "indirect_relrmse");
    ASSERT_LT(backend, rows[0].size());
    EXPECT_EQ(rows[1][1], "paper");
    EXPECT_EQ(rows[1][backend], "cpu");
    EXPECT_EQ(rows[2][1], "backend=gpu");
    EXPECT_EQ(rows[2][backend], "gpu");
    for (std::size_t r = 1; r < rows.size(); ++r) {
        const double error = cell_number(rows[r][indirect]);
        std::printf("[ figures  ] backend %s: indirect relRMSE %.4f after 6 frames\n",
                    rows[r][backend].c_str(), error);
        // 1 is the error of an IIM with nothing gathered: below it, the backend's gathers
        // reached the light maps.
        EXPECT_GE(error, 0.0) << rows[r][1];
        EXPECT_LT(error, 1.0) << rows[r][1];
    }
}

}  // namespace
