// Hostile values the JSON parser accepts: symbolic links out of the level's folder, indices that
// are not whole numbers, counts past the limits (refused before anything is allocated for
// them), and luxel extras of the wrong type. Each must end in a luxel::Error naming the file and
// what is wrong, never in silently dropped data.

#include <filesystem>
#include <fstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "gltf_test_files.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/scene/gltf.hpp"
#include "temp_dir.hpp"

namespace {

using luxel::testing::bytes_of;
using luxel::testing::GltfBuilder;
using luxel::testing::kTriangle;
using nlohmann::json;

constexpr const char* kName = "values.gltf";

std::string load_error(const std::string& text, const luxel::scene::LoadOptions& options = {}) {
    try {
        (void)luxel::scene::load_gltf_from_memory(bytes_of(text), kName, {}, options);
    } catch (const luxel::Error& e) {
        return e.what();
    }
    return "(loaded)";
}

GltfBuilder triangle() {
    GltfBuilder file;
    file.add_triangles(kTriangle, {0, 1, 2});
    return file;
}

void write_bytes(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes) {
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()),
               static_cast<std::streamsize>(bytes.size()));
}

TEST(GltfHostileValues, ASymbolicLinkOutOfTheFoldersIsRefused) {
    luxel::testing::TempDir dir;
    std::filesystem::create_directory(dir / "level");
    const GltfBuilder file = triangle();
    write_bytes(dir / "outside.bin", file.bin);
    // Inside the folder by name, outside by what it points to.
    std::filesystem::create_symlink(dir / "outside.bin", dir / "level" / "triangle.bin");
    json document = file.document;
    document["buffers"] = {{{"byteLength", file.bin.size()}, {"uri", "triangle.bin"}}};
    std::ofstream(dir / "level" / "level.gltf") << document.dump();
    try {
        (void)luxel::scene::load_gltf(dir / "level" / "level.gltf");
        FAIL() << "read a buffer through a link that leaves the level's folder";
    } catch (const luxel::Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("level.gltf"), std::string::npos) << message;
        EXPECT_NE(message.find("symbolic link to a file outside"), std::string::npos) << message;
    }

    // A link that stays inside the folder is fine, and so is a folder reached through a link.
    std::filesystem::remove(dir / "level" / "triangle.bin");
    write_bytes(dir / "level" / "real.bin", file.bin);
    std::filesystem::create_symlink(dir / "level" / "real.bin", dir / "level" / "triangle.bin");
    EXPECT_EQ(luxel::scene::load_gltf(dir / "level" / "level.gltf").triangle_count(), 1u);
    std::filesystem::create_directory_symlink(dir / "level", dir / "linked-level");
    const luxel::scene::Scene scene = luxel::scene::load_gltf(dir / "linked-level" / "level.gltf");
    EXPECT_EQ(scene.triangle_count(), 1u);
    ASSERT_EQ(scene.report.external_files.size(), 1u);
    EXPECT_EQ(scene.report.external_files[0],
              std::filesystem::canonical(dir / "level" / "real.bin"));
}

TEST(GltfHostileValues, IndicesMustBeWholeNumbers) {
    // tinygltf drops each of these without a word: the node would lose its mesh.
    const std::pair<json, std::string> cases[] = {
        {0.5, "nodes[0].mesh must be a whole number >= 0, got 0.5"},
        {-1, "nodes[0].mesh must be a whole number >= 0, got -1"},
        {"0", "nodes[0].mesh must be a whole number >= 0, got \"0\""},
        {json::array({0}), "nodes[0].mesh must be a whole number >= 0, got an array"},
    };
    for (const auto& [value, problem] : cases) {
        GltfBuilder file = triangle();
        file.document["nodes"][0]["mesh"] = value;
        const std::string message = load_error(file.text());
        EXPECT_EQ(message.rfind(std::string(kName) + ": ", 0), 0u) << message;
        EXPECT_NE(message.find(problem), std::string::npos) << message;
    }
    // Beyond 64 bits: the JSON parser reads it as a float.
    GltfBuilder file = triangle();
    std::string text = file.text();
    const std::string mesh_zero = "\"mesh\":0";
    text.replace(text.find(mesh_zero), mesh_zero.size(), "\"mesh\":18446744073709551616");
    EXPECT_NE(load_error(text).find("nodes[0].mesh must be a whole number"), std::string::npos)
        << load_error(text);
    // A whole number beyond what an index holds would wrap to mesh 0.
    text = file.text();
    text.replace(text.find(mesh_zero), mesh_zero.size(), "\"mesh\":4294967296");
    EXPECT_NE(load_error(text).find("4294967296 (beyond 2^31 - 1)"), std::string::npos)
        << load_error(text);

    file = triangle();
    file.document["accessors"][0]["count"] = 2.5;
    EXPECT_NE(load_error(file.text()).find("accessors[0].count must be a whole number"),
              std::string::npos);
    file = triangle();
    file.document["scenes"][0]["nodes"][0] = -3;
    EXPECT_NE(load_error(file.text()).find("scenes[0].nodes[0] must be a whole number"),
              std::string::npos);
    file = triangle();
    file.document["materials"] = {
        {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 1.5}}}}}}};
    EXPECT_NE(load_error(file.text())
                  .find("materials[0].pbrMetallicRoughness.baseColorTexture.index must be"),
              std::string::npos)
        << load_error(file.text());
    // Under extras anything goes: the glTF schema does not type it.
    file = triangle();
    file.document["nodes"][0]["extras"] = {{"mesh", 0.5}, {"count", "many"}};
    EXPECT_EQ(load_error(file.text()), "(loaded)");
}

TEST(GltfHostileValues, CountsPastTheLimitsAreRefusedBeforeTheyAreRead) {
    luxel::scene::LoadOptions options;
    options.max_nodes = 10;
    options.max_array_elements = 20;
    options.max_lights = 3;

    GltfBuilder file = triangle();
    for (int i = 0; i < 10; ++i) {
        file.document["nodes"].push_back(json::object());
    }
    std::string message = load_error(file.text(), options);
    EXPECT_NE(message.find("more than the limit of 10 nodes"), std::string::npos) << message;

    file = triangle();
    file.document["materials"] = json::array();
    for (int i = 0; i < 21; ++i) {
        file.document["materials"].push_back(json::object());
    }
    message = load_error(file.text(), options);
    EXPECT_NE(message.find("more than the limit of 20 materials"), std::string::npos) << message;

    file = triangle();
    json lights = json::array();
    for (int i = 0; i < 4; ++i) {
        lights.push_back({{"type", "point"}});
    }
    file.document["extensions"]["KHR_lights_punctual"]["lights"] = lights;
    file.document["extensionsUsed"] = {"KHR_lights_punctual"};
    message = load_error(file.text(), options);
    EXPECT_NE(message.find("more than the limit of 3 lights"), std::string::npos) << message;
    lights.erase(lights.begin());
    file.document["extensions"]["KHR_lights_punctual"]["lights"] = lights;
    EXPECT_EQ(load_error(file.text(), options), "(loaded)");
}

TEST(GltfHostileValues, PlacedLightsAreCountedOncePerNode) {
    // One light, placed by 300 nodes: 300 lights in the world, each with a shadow map.
    GltfBuilder file = triangle();
    file.document["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "point"}}};
    file.document["extensionsUsed"] = {"KHR_lights_punctual"};
    for (int i = 0; i < 300; ++i) {
        file.document["nodes"].push_back(
            {{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
        file.document["scenes"][0]["nodes"].push_back(i + 1);
    }
    std::string message = load_error(file.text());
    EXPECT_NE(message.find(kName), std::string::npos) << message;
    EXPECT_NE(message.find("300 placed lights would each get a shadow map when drawn, more than "
                           "the limit of 256 (shadowed-lights)"),
              std::string::npos)
        << message;

    luxel::scene::LoadOptions options;
    options.max_shadowed_lights = 300;
    EXPECT_EQ(load_error(file.text(), options), "(loaded)");
    options.max_light_instances = 299;
    message = load_error(file.text(), options);
    EXPECT_NE(message.find("300 nodes place a light, more than the limit of 299 "
                           "(light-instances)"),
              std::string::npos)
        << message;
    // Both are names --limit knows.
    EXPECT_NO_THROW(luxel::scene::set_load_limit(options, "shadowed-lights=1k"));
    EXPECT_EQ(options.max_shadowed_lights, 1024u);
    EXPECT_NO_THROW(luxel::scene::set_load_limit(options, "light-instances=2"));
    EXPECT_EQ(options.max_light_instances, 2u);
}

/// A PNG signature and IHDR declaring `width` x `height`: all a header read needs.
std::vector<std::uint8_t> png_header(std::uint32_t width, std::uint32_t height) {
    std::vector<std::uint8_t> bytes = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n',
                                       0,    0,   0,   13,  'I',  'H',  'D',  'R'};
    for (const std::uint32_t value : {width, height}) {
        for (int shift = 24; shift >= 0; shift -= 8) {
            bytes.push_back(static_cast<std::uint8_t>(value >> shift));
        }
    }
    for (const int byte : {8, 6, 0, 0, 0, 0, 0, 0, 0}) {  // RGBA8, then a CRC
        bytes.push_back(static_cast<std::uint8_t>(byte));
    }
    return bytes;
}

TEST(GltfHostileValues, LimitsOnHowThePartsCombine) {
    // Six nodes drawing one triangle: six instanced triangles.
    GltfBuilder file = triangle();
    for (int i = 0; i < 5; ++i) {
        file.document["nodes"].push_back({{"mesh", 0}});
        file.document["scenes"][0]["nodes"].push_back(i + 1);
    }
    luxel::scene::LoadOptions options;
    options.max_instanced_triangles = 5;
    std::string message = load_error(file.text(), options);
    EXPECT_NE(message.find("more than 5 triangles in all, counting each instance"),
              std::string::npos)
        << message;
    options.max_instanced_triangles = 6;
    EXPECT_EQ(load_error(file.text(), options), "(loaded)");

    // A forged layout: 64 pages of 4096^2 texels named in a few bytes.
    file = triangle();
    file.document["nodes"][0]["name"] = "floor";
    file.document["nodes"][0]["extras"]["luxel"]["lightmap"] = {{"texel_size", 0.05},
                                                                {"page_size", 4096},
                                                                {"surfaces",
                                                                 {{{"id", 0},
                                                                   {"primitive", 0},
                                                                   {"page", 63},
                                                                   {"rect", {0, 0, 1, 1}},
                                                                   {"charts", json::array()},
                                                                   {"area", 1.0},
                                                                   {"texels", 1}}}}};
    message = load_error(file.text());
    EXPECT_NE(message.find("64 pages of 4096^2 texels"), std::string::npos) << message;
    // The last page index an int holds: its count, one more, is counted in 64 bits (UBSan
    // reported the overflow in the hostile corpus's lm-pages-far-apart).
    file.document["nodes"][0]["extras"]["luxel"]["lightmap"]["surfaces"][0]["page"] = 2147483647;
    message = load_error(file.text());
    EXPECT_NE(message.find("2147483648 pages of 4096^2 texels"), std::string::npos) << message;
    file.document["nodes"][0]["extras"]["luxel"]["lightmap"]["surfaces"][0]["page"] = 63;
    file.document["nodes"][0]["extras"]["luxel"]["lightmap"]["page_size"] = 65536;
    message = load_error(file.text());
    EXPECT_NE(message.find("floor"), std::string::npos) << message;
    EXPECT_NE(message.find("page_size: must be within 1..8192"), std::string::npos) << message;
    // A surface's own texel size (luxel-prep's coarse texels for hidden surfaces) is checked too.
    file.document["nodes"][0]["extras"]["luxel"]["lightmap"]["page_size"] = 4096;
    file.document["nodes"][0]["extras"]["luxel"]["lightmap"]["surfaces"][0]["texel_size"] = -0.4;
    message = load_error(file.text());
    EXPECT_NE(message.find("surfaces[0].texel_size: must be a positive number of metres"),
              std::string::npos)
        << message;

    // Image pixels are summed from the headers, before anything is decoded.
    file = triangle();
    file.document["images"] = {
        {{"uri", "data:image/png;base64," + luxel::testing::to_base64(png_header(16, 16))}}};
    file.document["textures"] = {{{"source", 0}}};
    file.document["materials"] = {
        {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    file.document["meshes"][0]["primitives"][0]["material"] = 0;
    options = {};
    options.max_image_pixels = 255;
    message = load_error(file.text(), options);
    EXPECT_NE(message.find("more than 255 pixels in all"), std::string::npos) << message;
    EXPECT_NE(message.find("16x16"), std::string::npos) << message;
    options.max_image_pixels = 256;
    EXPECT_EQ(load_error(file.text(), options), "(loaded)");
}

TEST(GltfHostileValues, RadiometricProductsThatWouldOverflowAreRefused) {
    // Each factor is finite; their product is not (as float), nor are the powers made of it.
    GltfBuilder file = triangle();
    file.document["extensionsUsed"] = {"KHR_lights_punctual"};
    file.document["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "point"},
                                                                     {"name", "sun in a jar"},
                                                                     {"color", {1e20, 1, 1}},
                                                                     {"intensity", 1e20}}};
    file.document["nodes"].push_back({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    file.document["scenes"][0]["nodes"].push_back(1);
    std::string message = load_error(file.text());
    EXPECT_NE(message.find("sun in a jar"), std::string::npos) << message;
    EXPECT_NE(message.find("colour times intensity exceeds 1e20"), std::string::npos) << message;

    file = triangle();
    file.document["extensionsUsed"] = {"KHR_materials_emissive_strength"};
    file.document["materials"] = {
        {{"name", "lava"},
         {"emissiveFactor", {1, 1, 1}},
         {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 3e38}}}}}}};
    file.document["meshes"][0]["primitives"][0]["material"] = 0;
    message = load_error(file.text());
    EXPECT_NE(message.find("lava"), std::string::npos) << message;
    EXPECT_NE(message.find("emissive strength exceeds 1e20"), std::string::npos) << message;
}

TEST(GltfHostileValues, VolumeValuesOutOfRangeNameTheMaterial) {
    // KHR_materials_volume: each wrong value fails naming the material and the key.
    const auto volume_error = [](const nlohmann::json& volume) {
        GltfBuilder file = triangle();
        file.document["extensionsUsed"] = {"KHR_materials_volume"};
        file.document["materials"] = {
            {{"name", "smoked glass"}, {"extensions", {{"KHR_materials_volume", volume}}}}};
        file.document["meshes"][0]["primitives"][0]["material"] = 0;
        return load_error(file.text());
    };
    const std::vector<std::pair<nlohmann::json, std::string>> cases = {
        {{{"thicknessFactor", -0.1}}, "thicknessFactor must not be negative"},
        {{{"thicknessFactor", "thick"}}, "thicknessFactor is not a number"},
        {{{"attenuationDistance", 0.0}}, "attenuationDistance must be positive"},
        {{{"attenuationDistance", -2.0}}, "attenuationDistance must be positive"},
        {{{"attenuationColor", {1, 0.5}}}, "attenuationColor must be an array of three numbers"},
        {{{"attenuationColor", {1, "red", 0}}},
         "attenuationColor must be an array of three numbers"},
        {nlohmann::json::array(), "KHR_materials_volume is not an object"},
    };
    for (const auto& [volume, expected] : cases) {
        const std::string message = volume_error(volume);
        EXPECT_NE(message.find("smoked glass"), std::string::npos) << message;
        EXPECT_NE(message.find(expected), std::string::npos) << volume.dump() << ": " << message;
    }
}

/// A triangle under a parent, with a camera on a third node.
GltfBuilder triangle_with_camera() {
    GltfBuilder file = triangle();
    file.document["cameras"] = {
        {{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}};
    file.document["nodes"].push_back({{"name", "parent"}, {"children", {0, 2}}});
    file.document["nodes"].push_back({{"name", "eye"}, {"camera", 0}, {"translation", {0, 0, 3}}});
    file.document["scenes"][0]["nodes"] = {1};
    return file;
}

/// One LINEAR animation of `node`'s `path` from the first three keys at t = 0 to the next three
/// at t = 1.
void animate(GltfBuilder& file, int node, const std::string& path, const std::vector<float>& keys) {
    const int times = static_cast<int>(file.document["accessors"].size());
    file.document["animations"] = {
        {{"samplers", {{{"input", times}, {"output", times + 1}, {"interpolation", "LINEAR"}}}},
         {"channels", {{{"sampler", 0}, {"target", {{"node", node}, {"path", path}}}}}}}};
    file.add_accessor(file.add_view(std::vector<float>{0.0f, 1.0f}), 5126, 2, "SCALAR");
    file.document["accessors"][static_cast<std::size_t>(times)]["min"] = {0.0};
    file.document["accessors"][static_cast<std::size_t>(times)]["max"] = {1.0};
    file.add_accessor(file.add_view(keys), 5126, 2, "VEC3");
}

TEST(GltfHostileValues, TransformsAndCamerasThatWouldMakeNonFiniteRays) {
    GltfBuilder file = triangle_with_camera();
    ASSERT_EQ(load_error(file.text()), "(loaded)");

    file = triangle_with_camera();
    file.document["nodes"][1]["scale"] = {1e30, 1e30, 1e30};  // finite alone
    std::string message = load_error(file.text());
    EXPECT_NE(message.find("node 1 'parent'"), std::string::npos) << message;
    EXPECT_NE(message.find("can reach a scale of"), std::string::npos) << message;

    file = triangle_with_camera();
    file.document["nodes"][2]["scale"] = {0, 0, 0};
    message = load_error(file.text());
    EXPECT_NE(message.find("'eye': holds a camera but its world transform has no volume"),
              std::string::npos)
        << message;

    for (const auto& [key, value] : {std::pair<const char*, double>{"yfov", 1e-30},
                                     {"znear", 1e-40},
                                     {"aspectRatio", 1e-30}}) {
        file = triangle_with_camera();
        file.document["cameras"][0]["perspective"][key] = value;
        message = load_error(file.text());
        EXPECT_NE(message.find("camera 0"), std::string::npos) << key << ": " << message;
        EXPECT_NE(message.find("projection parameters out of range"), std::string::npos)
            << key << ": " << message;
    }

    // Keys near the float maximum: finite each, but interpolating between them overflows.
    file = triangle_with_camera();
    animate(file, 2, "translation", {3e38f, 3e38f, 3e38f, -3e38f, -3e38f, -3e38f});
    message = load_error(file.text());
    EXPECT_NE(message.find("'eye'"), std::string::npos) << message;
    EXPECT_NE(message.find("can reach a scale of"), std::string::npos) << message;
}

TEST(GltfHostileValues, OrthographicBoundsAreCheckedLikePerspectiveOnes) {
    const auto orthographic = [](double xmag, double ymag, double znear, double zfar) {
        GltfBuilder file = triangle_with_camera();
        file.document["cameras"] = {
            {{"type", "orthographic"},
             {"orthographic", {{"xmag", xmag}, {"ymag", ymag}, {"znear", znear}, {"zfar", zfar}}}}};
        return file;
    };
    EXPECT_EQ(load_error(orthographic(2.0, 1.5, 0.0, 100.0).text()), "(loaded)");
    EXPECT_EQ(load_error(orthographic(-2.0, 1e-6, 0.0, 1e-6).text()), "(loaded)");
    // Each passed "finite and not 0" and still made the projection, or its inverse, Inf.
    for (const auto& [xmag, ymag, znear, zfar] :
         {std::tuple{1.0, 1e-40, 0.0, 100.0}, std::tuple{3e38, 3e38, 0.0, 100.0},
          std::tuple{1.0, 1e7, 0.0, 100.0}, std::tuple{1e-7, 1.0, 0.0, 100.0},
          std::tuple{1.0, 1.0, 5.0, 5.0}, std::tuple{1.0, 1.0, 0.0, 1e-40}}) {
        const std::string message = load_error(orthographic(xmag, ymag, znear, zfar).text());
        const std::string values = std::to_string(xmag) + " " + std::to_string(ymag) + " " +
                                   std::to_string(zfar) + ": " + message;
        EXPECT_NE(message.find(kName), std::string::npos) << values;
        EXPECT_NE(message.find("camera 0 (on node 2 'eye')"), std::string::npos) << values;
        EXPECT_NE(message.find("orthographic: xmag and ymag of magnitude in [1e-6, 1e6]"),
                  std::string::npos)
            << values;
    }
}

TEST(GltfHostileValues, AMovingMeshMayNotShrinkBeyondWhatItsInverseHolds) {
    // Scaled to 0 by its animation: playback keeps it at 1e-6 (world::update_animations), which
    // the ray tracer can invert, so the file loads.
    GltfBuilder file = triangle_with_camera();
    animate(file, 0, "scale", {1, 1, 1, 0, 0, 0});
    EXPECT_EQ(load_error(file.text()), "(loaded)");

    // Under a parent scaled by 1e-4, that is 1e-10: no longer invertible in float.
    file.document["nodes"][1]["scale"] = {1e-4, 1e-4, 1e-4};
    std::string message = load_error(file.text());
    EXPECT_NE(message.find(kName), std::string::npos) << message;
    EXPECT_NE(message.find("node 0: a moving mesh"), std::string::npos) << message;
    EXPECT_NE(message.find("can shrink to a scale of 1e-10"), std::string::npos) << message;

    // Keys of opposite sign pass through 0 too; the parent's own animation moves the mesh.
    file = triangle_with_camera();
    file.document["nodes"][0]["scale"] = {1e-4, 1e-4, 1e-4};
    animate(file, 1, "scale", {1, 1, 1, 1, -1, 1});
    message = load_error(file.text());
    EXPECT_NE(message.find("node 0: a moving mesh"), std::string::npos) << message;

    // A mesh flagged dynamic with a zero scale at rest is placed as an instance as it is.
    file = triangle_with_camera();
    file.document["nodes"][0]["scale"] = {1, 0, 1};
    file.document["nodes"][0]["extras"] = {{"luxel", {{"dynamic", true}}}};
    message = load_error(file.text());
    EXPECT_NE(message.find("can shrink to a scale of 0"), std::string::npos) << message;
    // Without the flag it is baked into world space: a flat mesh, nothing to invert.
    file.document["nodes"][0].erase("extras");
    EXPECT_EQ(load_error(file.text()), "(loaded)");
}

TEST(GltfHostileValues, LuxelExtrasOfTheWrongTypeNameTheNodeAndTheKey) {
    const std::pair<json, std::string> cases[] = {
        {{{"bounce", "high"}}, "extras.luxel.bounce must be a JSON object, got string"},
        {{{"bounce", {{"height", "high"}}}}, "extras.luxel.bounce.height must be a finite number"},
        {{{"switch", {{"period", true}}}}, "extras.luxel.switch.period must be a finite number"},
        {{{"wave", {{"direction", {1, "x"}}}}}, "extras.luxel.wave.direction must be two numbers"},
        {{{"wave", {{"wavelength", 0}}}}, "extras.luxel.wave.wavelength must be more than 0"},
        {{{"wave", {{"wavelength", 0.1}, {"amplitude", 0.5}}}},
         "extras.luxel.wave.amplitude must be from 0 to the wavelength"},
        {{{"wave", {{"amplitude", -0.01}}}}, "extras.luxel.wave.amplitude must be from 0"},
        {{{"wave", {{"direction", {0, 0}}}}}, "extras.luxel.wave.direction must not be [0, 0]"},
        {{{"furnace", 2}}, "extras.luxel.furnace must be true or false (or 1 or 0), got 2"},
        {{{"dynamic", "yes"}},
         "extras.luxel.dynamic must be true or false (or 1 or 0), got \"yes\""},
        {{{"enabled", 0.5}}, "extras.luxel.enabled must be true or false (or 1 or 0), got 0.5"},
        {{{"portal", "window"}}, "extras.luxel.portal must be true or false (or 1 or 0)"},
        {{{"portal", 2}}, "extras.luxel.portal must be true or false (or 1 or 0), got 2"},
        {{{"lightmap", 7}}, "extras.luxel.lightmap must be a JSON object"},
        {{{"light_radius", -0.1}}, "extras.luxel.light_radius must be a number of metres from 0"},
        {{{"light_radius", 1000}}, "extras.luxel.light_radius must be a number of metres from 0"},
        {{{"light_radius", "10 cm"}}, "extras.luxel.light_radius must be a number of metres"},
        {{{"light_radius", nullptr}}, "extras.luxel.light_radius must be a number of metres"},
    };
    for (const auto& [luxel, problem] : cases) {
        GltfBuilder file = triangle();
        file.document["nodes"][0]["name"] = "crate";
        file.document["nodes"][0]["extras"]["luxel"] = luxel;
        const std::string message = load_error(file.text());
        EXPECT_EQ(message.rfind(std::string(kName) + ": ", 0), 0u) << message;
        EXPECT_NE(message.find("crate"), std::string::npos) << message;
        EXPECT_NE(message.find(problem), std::string::npos) << message;
    }
    GltfBuilder file = triangle();
    file.document["nodes"][0]["extras"]["luxel"] = {{"bounce", {{"height", 1.0}, {"period", 2}}}};
    EXPECT_EQ(load_error(file.text()), "(loaded)");
}

}  // namespace

namespace {

TEST(GltfHostileValues, BooleanFlagsAcceptBlendersIntegers) {
    // Blender 3 keeps a boolean custom property as the integer 1 or 0 and its glTF exporter
    // writes it so: a level made there must load with its flags as meant.
    for (const int value : {0, 1}) {
        GltfBuilder file = triangle();
        file.document["nodes"][0]["extras"]["luxel"] = {{"dynamic", value}, {"enabled", value}};
        const luxel::scene::Scene scene =
            luxel::scene::load_gltf_from_memory(bytes_of(file.text()), kName, {}, {});
        ASSERT_EQ(scene.nodes.size(), 1u);
        ASSERT_TRUE(scene.nodes[0].flags.dynamic.has_value());
        EXPECT_EQ(*scene.nodes[0].flags.dynamic, value == 1);
        EXPECT_EQ(scene.nodes[0].flags.light_enabled, value == 1);
    }
}

TEST(GltfHostileValues, ALightRadiusInRangeIsReadInMetres) {
    for (const double radius : {0.0, 0.1, 100.0}) {
        GltfBuilder file = triangle();
        file.document["nodes"][0]["extras"]["luxel"] = {{"light_radius", radius}};
        const luxel::scene::Scene scene =
            luxel::scene::load_gltf_from_memory(bytes_of(file.text()), kName, {}, {});
        ASSERT_EQ(scene.nodes.size(), 1u);
        EXPECT_FLOAT_EQ(scene.nodes[0].flags.light_radius, static_cast<float>(radius));
    }
    const luxel::scene::Scene plain =
        luxel::scene::load_gltf_from_memory(bytes_of(triangle().text()), kName, {}, {});
    EXPECT_EQ(plain.nodes[0].flags.light_radius, 0.0f);
}

}  // namespace
