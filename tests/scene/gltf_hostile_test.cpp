// Hostile and broken glTF files: each must end in a luxel::Error whose message names the file
// and the problem, never in a crash, a hang or an allocation the file does not justify.

#include <cmath>
#include <fstream>
#include <limits>

#include <gtest/gtest.h>

#include "gltf_test_files.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/scene/gltf.hpp"
#include "temp_dir.hpp"
#include "test_scenes.hpp"

namespace {

using luxel::testing::bytes_of;
using luxel::testing::GltfBuilder;
using luxel::testing::kTriangle;
using nlohmann::json;

constexpr const char* kName = "hostile.gltf";

/// Loads `bytes` expecting a luxel::Error that starts with the file's name and contains
/// `problem`.
void expect_rejected(const std::vector<std::uint8_t>& bytes, const std::string& problem,
                     const luxel::scene::LoadOptions& options = {},
                     const std::filesystem::path& base_dir = {}) {
    try {
        const luxel::scene::Scene scene =
            luxel::scene::load_gltf_from_memory(bytes, kName, base_dir, options);
        FAIL() << "loaded a file that should be rejected for: " << problem;
    } catch (const luxel::Error& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.rfind(std::string(kName) + ": ", 0), 0u) << message;
        EXPECT_NE(message.find(problem), std::string::npos)
            << "expected '" << problem << "' in: " << message;
    }
}

void expect_rejected(const std::string& text, const std::string& problem,
                     const luxel::scene::LoadOptions& options = {}) {
    expect_rejected(bytes_of(text), problem, options);
}

GltfBuilder triangle() {
    GltfBuilder file;
    file.add_triangles(kTriangle, {0, 1, 2});
    return file;
}

void write_file(const std::filesystem::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

TEST(GltfHostile, EmptyAndMissingFiles) {
    expect_rejected(std::vector<std::uint8_t>{}, "the file is empty");
    luxel::testing::TempDir dir;
    try {
        (void)luxel::scene::load_gltf(dir / "absent.glb");
        FAIL();
    } catch (const luxel::Error& e) {
        EXPECT_EQ(std::string(e.what()).rfind((dir / "absent.glb").string() + ": ", 0), 0u);
        EXPECT_NE(std::string(e.what()).find("no such file"), std::string::npos) << e.what();
    }
    EXPECT_THROW((void)luxel::scene::load_gltf(dir.path()), luxel::Error);  // a directory
}

TEST(GltfHostile, TruncatedGlb) {
    const std::vector<std::uint8_t> glb = triangle().glb();
    for (const std::size_t length :
         {std::size_t{3}, std::size_t{11}, std::size_t{19}, glb.size() / 2, glb.size() - 4}) {
        expect_rejected(std::vector<std::uint8_t>(
                            glb.begin(), glb.begin() + static_cast<std::ptrdiff_t>(length)),
                        "truncated GLB");
    }
}

TEST(GltfHostile, GlbChunkLengthsPastTheEnd) {
    std::vector<std::uint8_t> glb = triangle().glb();
    const std::uint32_t json_length = luxel::testing::get_u32(glb, 12);
    // The BIN chunk claims 8 bytes more than there are: tinygltf's own check lets this by.
    const std::size_t bin_header = 20 + json_length;
    const std::uint32_t bin_length = luxel::testing::get_u32(glb, bin_header) + 8;
    std::memcpy(glb.data() + bin_header, &bin_length, 4);
    expect_rejected(glb, "truncated GLB: chunk 1");
    // A JSON chunk length near 4 GiB must not wrap around.
    std::vector<std::uint8_t> huge = triangle().glb();
    const std::uint32_t almost_4g = 0xFFFFFFF0u;
    std::memcpy(huge.data() + 12, &almost_4g, 4);
    expect_rejected(huge, "truncated GLB: chunk 0");
}

TEST(GltfHostile, GlbWrongVersionAndLength) {
    std::vector<std::uint8_t> glb = triangle().glb();
    glb[4] = 1;
    expect_rejected(glb, "GLB version 1");
    glb = triangle().glb();
    glb.push_back(0);
    expect_rejected(glb, "header says");
}

TEST(GltfHostile, InvalidJson) {
    expect_rejected(std::string("{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [}"),
                    "invalid JSON");
    expect_rejected(std::string("\x01\x02\x03\x04 not json"), "invalid JSON");
    expect_rejected(std::string("[1, 2, 3]"), "invalid glTF");  // JSON, but not an object
    expect_rejected(std::string("{\"nodes\": []}"), "asset");   // no asset object
    // Invalid JSON inside a well-formed GLB container.
    expect_rejected(luxel::testing::make_glb("{\"asset\": ", {}), "invalid JSON");
}

TEST(GltfHostile, DeeplyNestedJson) {
    std::string deep = "{\"asset\": {\"version\": \"2.0\"}, \"extras\": ";
    deep += std::string(100000, '[') + std::string(100000, ']') + "}";
    expect_rejected(deep, "nested deeper than 256 levels");
}

TEST(GltfHostile, MissingAndShortBufferFile) {
    luxel::testing::TempDir dir;
    GltfBuilder file = triangle();
    json document = file.document;
    document["buffers"] = {{{"byteLength", file.bin.size()}, {"uri", "triangle.bin"}}};
    write_file(dir / "triangle.gltf", document.dump());

    const auto expect_file_error = [&](const std::string& problem) {
        try {
            (void)luxel::scene::load_gltf(dir / "triangle.gltf");
            FAIL() << "loaded without a usable buffer file";
        } catch (const luxel::Error& e) {
            const std::string message = e.what();
            EXPECT_EQ(message.rfind((dir / "triangle.gltf").string() + ": ", 0), 0u) << message;
            EXPECT_NE(message.find(problem), std::string::npos) << message;
        }
    };
    expect_file_error("triangle.bin");  // missing
    write_file(dir / "triangle.bin",
               std::string(reinterpret_cast<const char*>(file.bin.data()), file.bin.size() - 4));
    expect_file_error("size mismatch");
    write_file(dir / "triangle.bin",
               std::string(reinterpret_cast<const char*>(file.bin.data()), file.bin.size()));
    EXPECT_EQ(luxel::scene::load_gltf(dir / "triangle.gltf").triangle_count(), 1u);
}

TEST(GltfHostile, ExternalFilesStayInsideTheDirectory) {
    luxel::testing::TempDir dir;
    std::filesystem::create_directory(dir / "level");
    GltfBuilder file = triangle();
    write_file(dir / "secret.bin",
               std::string(reinterpret_cast<const char*>(file.bin.data()), file.bin.size()));
    json document = file.document;
    document["buffers"] = {{{"byteLength", file.bin.size()}, {"uri", "../secret.bin"}}};
    expect_rejected(bytes_of(document.dump()), "outside the file's directory", {}, dir / "level");
    document["buffers"][0]["uri"] = (dir / "secret.bin").string();  // absolute: made relative
    expect_rejected(bytes_of(document.dump()), "does not exist", {}, dir / "level");
    // From memory without a directory, no external file is read at all.
    document["buffers"][0]["uri"] = "secret.bin";
    expect_rejected(bytes_of(document.dump()), "no directory was given");
}

TEST(GltfHostile, AccessorOutOfItsBufferView) {
    GltfBuilder file = triangle();
    file.document["accessors"][0]["count"] = 4;  // 4 vec3 in a 36-byte view
    expect_rejected(file.text(), "run past the end of bufferView 0");
    file = triangle();
    file.document["accessors"][0]["byteOffset"] = 4;
    expect_rejected(file.text(), "run past the end of bufferView 0");
    file = triangle();
    file.document["bufferViews"][0]["byteStride"] = 16;  // 3 elements at stride 16 need 44
    expect_rejected(file.text(), "run past the end of bufferView 0");
}

TEST(GltfHostile, BufferViewOutOfItsBuffer) {
    GltfBuilder file = triangle();
    file.document["bufferViews"][1]["byteOffset"] = 1000;
    expect_rejected(file.text(), "runs past the end of buffer 0");
    file = triangle();
    // Offset + length wrapping around 2^64 must not look small.
    file.document["bufferViews"][1]["byteOffset"] = std::numeric_limits<std::uint64_t>::max() - 2;
    expect_rejected(file.text(), "runs past the end of buffer 0");
    // An image inside a bufferView that lies outside the buffer (tinygltf does not check).
    file = triangle();
    file.document["images"] = {{{"bufferView", 0}, {"mimeType", "image/png"}}};
    file.document["bufferViews"][0]["byteLength"] = 4096;
    expect_rejected(file.glb(), "does not lie inside buffer 0");
}

TEST(GltfHostile, AccessorIndexOutOfRange) {
    GltfBuilder file = triangle();
    file.document["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 99;
    expect_rejected(file.text(), "accessor 99 (POSITION of mesh 0 primitive 0): out of range");
    file = triangle();
    file.document["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = -5;
    // Caught by the JSON pre-check, before tinygltf reads it (gltf_json_check.cpp).
    expect_rejected(file.text(), "attributes.NORMAL must be a whole number >= 0, got -5");
    file = triangle();
    file.document["accessors"][0]["bufferView"] = 7;
    expect_rejected(file.text(), "bufferView 7 out of range");
}

TEST(GltfHostile, WrongAccessorTypes) {
    GltfBuilder file = triangle();
    file.document["accessors"][0]["type"] = "VEC2";
    expect_rejected(file.text(), "type VEC2, expected VEC3");
    file = triangle();
    file.document["accessors"][1]["componentType"] = 5126;  // float indices
    expect_rejected(file.text(), "FLOAT components are not allowed");
}

TEST(GltfHostile, IndexOutOfRange) {
    GltfBuilder file;
    file.add_triangles(kTriangle, {0, 1, 3});
    expect_rejected(file.text(), "index 2 is 3, out of range for 3 vertices");
    expect_rejected(file.glb(), "index 2 is 3, out of range for 3 vertices");
}

TEST(GltfHostile, NonFinitePositions) {
    for (const float bad :
         {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
          -std::numeric_limits<float>::infinity()}) {
        std::vector<float> positions = kTriangle;
        positions[4] = bad;
        GltfBuilder file;
        file.add_triangles(positions, {0, 1, 2});
        expect_rejected(file.glb(), "POSITION of mesh 0 primitive 0): element 1 is not finite");
    }
}

TEST(GltfHostile, NonFiniteNumbersInJson) {
    // JSON has no NaN or infinity; a number too large for a double is a JSON error, one too
    // large for a float is caught when converted.
    GltfBuilder file = triangle();
    const std::string text = file.text();
    const std::size_t mesh = text.find("\"mesh\":0");
    ASSERT_NE(mesh, std::string::npos);
    std::string overflow = text;
    overflow.replace(mesh, 8, "\"mesh\":0,\"translation\":[1e999,0,0]");
    expect_rejected(overflow, "invalid JSON: number overflow");
    std::string too_big = text;
    too_big.replace(mesh, 8, "\"mesh\":0,\"translation\":[1e300,0,0]");
    expect_rejected(too_big, "node 0 translation is not a finite number");
}

TEST(GltfHostile, DegenerateTrianglesAreDroppedAndCounted) {
    // Four triangles: one good, one repeating a vertex, one of zero area (collinear), and one
    // good again.
    const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0};
    GltfBuilder file;
    file.add_triangles(positions, {0, 1, 2, 0, 0, 2, 0, 1, 3, 2, 1, 0});
    const luxel::scene::Scene scene =
        luxel::scene::load_gltf_from_memory(bytes_of(file.text()), kName);
    EXPECT_EQ(scene.report.degenerate_triangles_dropped, 2u);
    EXPECT_EQ(scene.triangle_count(), 2u);
    EXPECT_EQ(scene.meshes[0].primitives[0].indices,
              (std::vector<std::uint32_t>{0, 1, 2, 2, 1, 0}));
    // All degenerate: the primitive goes, with a warning.
    GltfBuilder flat;
    flat.add_triangles(positions, {0, 1, 3});
    const luxel::scene::Scene empty =
        luxel::scene::load_gltf_from_memory(bytes_of(flat.text()), kName);
    EXPECT_EQ(empty.report.degenerate_triangles_dropped, 1u);
    EXPECT_TRUE(empty.meshes[0].primitives.empty());
    EXPECT_FALSE(empty.report.warnings.empty());
}

TEST(GltfHostile, AbsurdCountsAreRejectedBeforeAllocating) {
    GltfBuilder file = triangle();
    file.document["accessors"][0]["count"] = std::uint64_t{1} << 31;
    const std::string text = file.text();
    ASSERT_LT(text.size(), 1024u);
    expect_rejected(text, "count 2147483648 exceeds the limit");
    // With the limit lifted, the bounds check still refuses before anything is sized: under
    // the sanitizer build a 24 GiB allocation would abort the test.
    luxel::scene::LoadOptions lifted;
    lifted.max_accessor_elements = std::uint64_t{1} << 40;
    expect_rejected(text, "run past the end of bufferView 0", lifted);
    file.document["accessors"][0]["count"] = std::numeric_limits<std::uint64_t>::max();
    expect_rejected(file.text(), "exceeds the limit", lifted);
    // Triangle and node limits.
    luxel::scene::LoadOptions tight;
    tight.max_total_triangles = 0;
    expect_rejected(triangle().text(), "exceeds the limit of 0 triangles", tight);
    tight = {};
    tight.max_nodes = 0;
    expect_rejected(triangle().text(), "more than the limit of 0", tight);
    tight = {};
    tight.max_file_size = 16;
    expect_rejected(triangle().text(), "more than the limit of 16", tight);
}

TEST(GltfHostile, CyclicAndMultiParentNodeGraphs) {
    GltfBuilder file = triangle();
    file.document["nodes"] = {{{"children", {1}}}, {{"children", {0}}}};
    file.document["scenes"] = {{{"nodes", json::array()}}};
    expect_rejected(file.text(), "cycle in the node hierarchy");

    file.document["nodes"] = {{{"children", {0}}}};
    expect_rejected(file.text(), "node 0: is its own child");

    file.document["nodes"] = {{{"children", {2}}}, {{"children", {2}}}, json::object()};
    file.document["scenes"] = {{{"nodes", {0, 1}}}};
    expect_rejected(file.text(), "node 2 has two parents (nodes 0 and 1)");

    file.document["nodes"] = {{{"children", {1, 1}}}, json::object()};
    file.document["scenes"] = {{{"nodes", {0}}}};
    expect_rejected(file.text(), "node 0: lists child 1 twice");

    file.document["nodes"] = {{{"children", {1}}}, json::object()};
    file.document["scenes"] = {{{"nodes", {1}}}};
    expect_rejected(file.text(), "listed as a root but has a parent");

    // A long chain is fine up to the depth limit.
    file.document["nodes"] = json::array();
    for (int i = 0; i < 50; ++i) {
        file.document["nodes"].push_back(i < 49 ? json{{"children", {i + 1}}} : json::object());
    }
    file.document["scenes"] = {{{"nodes", {0}}}};
    EXPECT_EQ(luxel::scene::load_gltf_from_memory(bytes_of(file.text()), kName).nodes.size(), 50u);
    luxel::scene::LoadOptions shallow;
    shallow.max_node_depth = 10;
    expect_rejected(file.text(), "nested deeper than the limit of 10", shallow);
}

TEST(GltfHostile, UnsupportedRequiredExtensions) {
    GltfBuilder file = triangle();
    file.document["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    file.document["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    expect_rejected(file.text(), "requires the extension 'KHR_draco_mesh_compression'");
    file.document["extensionsUsed"] = {"KHR_texture_transform"};
    file.document["extensionsRequired"] = {"KHR_texture_transform"};
    expect_rejected(file.text(), "'KHR_texture_transform'");
    // Used but not required: loads.
    file.document["extensionsRequired"] = json::array();
    EXPECT_NO_THROW((void)luxel::scene::load_gltf_from_memory(bytes_of(file.text()), kName));
    file.document["extensionsUsed"] = {"KHR_lights_punctual", "KHR_materials_ior"};
    file.document["extensionsRequired"] = {"KHR_lights_punctual", "KHR_materials_ior"};
    EXPECT_NO_THROW((void)luxel::scene::load_gltf_from_memory(bytes_of(file.text()), kName));
}

TEST(GltfHostile, SparseAccessorsAreRejectedClearly) {
    GltfBuilder file = triangle();
    const int indices_view = file.add_view(std::vector<std::uint16_t>{1, 0});
    const int values_view = file.add_view(std::vector<float>{5, 5, 5});
    file.document["accessors"][0]["sparse"] = {
        {"count", 1},
        {"indices", {{"bufferView", indices_view}, {"componentType", 5123}}},
        {"values", {{"bufferView", values_view}}}};
    expect_rejected(file.text(), "sparse accessors are not supported");
}

TEST(GltfHostile, BadAnimations) {
    const auto animated = [](std::vector<float> times, std::vector<float> values,
                             const std::string& interpolation) {
        GltfBuilder file = triangle();
        const int input = file.add_accessor(file.add_view(times), 5126, times.size(), "SCALAR");
        const int output =
            file.add_accessor(file.add_view(values), 5126, values.size() / 3, "VEC3");
        file.document["animations"] = {
            {{"samplers",
              {{{"input", input}, {"output", output}, {"interpolation", interpolation}}}},
             {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}}}}};
        return file;
    };
    expect_rejected(animated({0, 1, 1}, std::vector<float>(9, 0.0f), "LINEAR").text(),
                    "keyframe times must increase strictly");
    expect_rejected(animated({0, 2, 1}, std::vector<float>(9, 0.0f), "STEP").text(),
                    "keyframe times must increase strictly");
    expect_rejected(animated({-1, 1}, std::vector<float>(6, 0.0f), "LINEAR").text(),
                    "keyframe time 0 is negative");
    expect_rejected(animated({0, std::numeric_limits<float>::quiet_NaN()},
                             std::vector<float>(6, 0.0f), "LINEAR")
                        .text(),
                    "is not finite");
    expect_rejected(animated({0, 1}, std::vector<float>(9, 0.0f), "LINEAR").text(),
                    "output has 3 values for 2 keyframes, expected 2");
    expect_rejected(animated({0, 1}, std::vector<float>(6, 0.0f), "CUBICSPLINE").text(),
                    "expected 6 (in-tangent, value, out-tangent)");
    expect_rejected(animated({0, 1}, std::vector<float>(6, 0.0f), "BOUNCY").text(),
                    "unknown interpolation 'BOUNCY'");
    GltfBuilder file = animated({0, 1}, std::vector<float>(6, 0.0f), "LINEAR");
    file.document["animations"][0]["channels"][0]["target"]["node"] = 12;
    expect_rejected(file.text(), "target node 12 out of range");
    file = animated({0, 1}, std::vector<float>(6, 0.0f), "LINEAR");
    file.document["animations"][0]["channels"].push_back(
        file.document["animations"][0]["channels"][0]);
    expect_rejected(file.text(), "already animated by another channel");
    // A weights channel is skipped with a warning; the file loads.
    file = animated({0, 1}, std::vector<float>(6, 0.0f), "LINEAR");
    file.document["animations"][0]["channels"][0]["target"]["path"] = "weights";
    const luxel::scene::Scene scene =
        luxel::scene::load_gltf_from_memory(bytes_of(file.text()), kName);
    EXPECT_TRUE(scene.animations.empty());
    ASSERT_EQ(scene.report.warnings.size(), 1u);
    EXPECT_NE(scene.report.warnings[0].find("weights"), std::string::npos);
}

TEST(GltfHostile, BadReferencesAndValues) {
    GltfBuilder file = triangle();
    file.document["meshes"][0]["primitives"][0]["material"] = 3;
    expect_rejected(file.text(), "material 3 out of range");
    file = triangle();
    file.document["nodes"][0]["mesh"] = 5;
    expect_rejected(file.text(), "node 0: mesh 5 out of range");
    file = triangle();
    file.document["nodes"][0]["rotation"] = {0, 0, 0, 0};
    expect_rejected(file.text(), "rotation is not a unit quaternion");
    file = triangle();
    file.document["nodes"][0]["translation"] = {1, 2};
    expect_rejected(file.text(), "translation has 2 numbers, expected 3");
    file = triangle();
    file.document["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0.5, 0, 0, 0, 1};
    expect_rejected(file.text(), "matrix is not affine");
    file = triangle();
    file.document["nodes"][0]["extensions"]["KHR_lights_punctual"]["light"] = 0;
    expect_rejected(file.text(), "light 0 out of range");
    file = triangle();
    file.document["extensions"]["KHR_lights_punctual"]["lights"] = {
        {{"type", "spot"}, {"spot", {{"innerConeAngle", 1.0}, {"outerConeAngle", 0.5}}}}};
    expect_rejected(file.text(), "spot cone angles");
    file.document["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "laser"}}};
    expect_rejected(file.text(), "unknown type 'laser'");
    file = triangle();
    file.document["nodes"][0]["extras"] = {{"luxel", {{"dynamic", "yes"}}}};
    expect_rejected(file.text(), "extras.luxel.dynamic must be true or false");
    file = triangle();
    file.document["cameras"] = {
        {{"type", "perspective"}, {"perspective", {{"yfov", -1.0}, {"znear", 0.1}}}}};
    expect_rejected(file.text(), "camera 0: projection parameters out of range");
    file = triangle();
    file.document["materials"] = {{{"extensions", {{"KHR_materials_ior", {{"ior", 0.5}}}}}}};
    expect_rejected(file.text(), "ior 0.5");
    file = triangle();
    file.document["scene"] = 4;
    expect_rejected(file.text(), "default scene 4 out of range");
}

TEST(GltfHostile, UnsupportedModesAreSkippedAndCounted) {
    GltfBuilder file = triangle();
    file.document["meshes"][0]["primitives"][0]["mode"] = 1;  // lines
    const luxel::scene::Scene lines =
        luxel::scene::load_gltf_from_memory(bytes_of(file.text()), kName);
    EXPECT_EQ(lines.report.primitives_skipped, 1u);
    EXPECT_TRUE(lines.meshes[0].primitives.empty());
    ASSERT_FALSE(lines.report.warnings.empty());
    EXPECT_NE(lines.report.warnings[0].find("mode 1"), std::string::npos);
}

TEST(GltfAccessors, StripsFansAndEveryComponentType) {
    // A quad as a strip (0 1 2 3) and as a fan (0 1 2 3), indices as bytes, texture
    // coordinates as normalized bytes and shorts.
    const std::vector<float> quad = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    for (const int mode : {5, 6}) {
        GltfBuilder file;
        json primitive;
        primitive["attributes"]["POSITION"] =
            file.add_accessor(file.add_view(quad), 5126, 4, "VEC3");
        primitive["attributes"]["TEXCOORD_0"] = file.add_accessor(
            file.add_view(std::vector<std::uint8_t>{0, 0, 255, 0, 0, 255, 255, 255}), 5121, 4,
            "VEC2", true);
        primitive["attributes"]["TEXCOORD_1"] = file.add_accessor(
            file.add_view(std::vector<std::uint16_t>{0, 0, 65535, 0, 0, 32768, 65535, 65535}), 5123,
            4, "VEC2", true);
        const std::vector<std::uint8_t> order = mode == 5 ? std::vector<std::uint8_t>{0, 1, 2, 3}
                                                          : std::vector<std::uint8_t>{0, 1, 3, 2};
        primitive["indices"] = file.add_accessor(file.add_view(order), 5121, 4, "SCALAR");
        primitive["mode"] = mode;
        file.document["meshes"] = {{{"primitives", {primitive}}}};
        file.document["nodes"] = {{{"mesh", 0}}};
        const luxel::scene::Scene scene =
            luxel::scene::load_gltf_from_memory(bytes_of(file.text()), kName);
        const luxel::scene::Primitive& p = scene.meshes[0].primitives[0];
        ASSERT_EQ(p.triangle_count(), 2u) << "mode " << mode;
        // Both triangles face +z (counter-clockwise from the front), as the spec's winding
        // rules make them.
        for (std::size_t t = 0; t < 2; ++t) {
            const glm::vec3 a = p.positions[p.indices[3 * t]];
            const glm::vec3 b = p.positions[p.indices[3 * t + 1]];
            const glm::vec3 c = p.positions[p.indices[3 * t + 2]];
            EXPECT_GT(glm::cross(b - a, c - a).z, 0.0f) << "mode " << mode << " triangle " << t;
        }
        EXPECT_FLOAT_EQ(p.texcoords0[1].x, 1.0f);
        EXPECT_FLOAT_EQ(p.texcoords1[2].y, 32768.0f / 65535.0f);
        EXPECT_EQ(scene.roots, std::vector<int>{0});  // no scenes: parentless nodes are roots
    }
}

TEST(GltfAccessors, InterleavedAndNonIndexed) {
    // Positions interleaved with normals (stride 24) and no indices.
    const std::vector<float> interleaved = {0, 0, 0, 0, 0, 2, 1, 0, 0, 0, 0, 2, 0, 1, 0, 0, 0, 2};
    GltfBuilder file;
    const int view = file.add_view(interleaved);
    file.document["bufferViews"][view]["byteStride"] = 24;
    json primitive;
    primitive["attributes"]["POSITION"] = file.add_accessor(view, 5126, 3, "VEC3");
    primitive["attributes"]["NORMAL"] = file.add_accessor(view, 5126, 3, "VEC3");
    file.document["accessors"][1]["byteOffset"] = 12;
    file.document["meshes"] = {{{"primitives", {primitive}}}};
    file.document["nodes"] = {{{"mesh", 0}}};
    const luxel::scene::Scene scene =
        luxel::scene::load_gltf_from_memory(file.glb(), "interleaved.glb");
    const luxel::scene::Primitive& p = scene.meshes[0].primitives[0];
    EXPECT_EQ(p.indices, (std::vector<std::uint32_t>{0, 1, 2}));
    EXPECT_EQ(p.positions[1], glm::vec3(1, 0, 0));
    EXPECT_EQ(p.normals[2], glm::vec3(0, 0, 1));  // normalised on load
}

}  // namespace
