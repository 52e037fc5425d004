// Errors found after a level has loaded (an image whose header reads but whose data does not
// decode, a light-map table naming a primitive the mesh lacks) must still name the level file:
// the scene carries it (Scene::source) to where they are found.

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <stb_image_write.h>

#include "gltf_test_files.hpp"
#include "luxel/ecs/registry.hpp"
#include "luxel/ecs/transform_system.hpp"
#include "luxel/lighting/core/photon_world.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/world/scene_instance.hpp"
#include "temp_dir.hpp"

namespace {

using namespace luxel;
using luxel::testing::GltfBuilder;
using nlohmann::json;

void append_bytes(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(context);
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    out->insert(out->end(), bytes, bytes + size);
}

/// A 32x32 PNG of noise (so that its data is not a few bytes), cut inside its image data: the
/// header reads, the pixels do not.
std::vector<std::uint8_t> truncated_png() {
    std::vector<std::uint8_t> pixels(32 * 32 * 3);
    std::uint32_t state = 12345;
    for (auto& p : pixels) {
        state = state * 1664525u + 1013904223u;
        p = static_cast<std::uint8_t>(state >> 24);
    }
    std::vector<std::uint8_t> png;
    EXPECT_NE(stbi_write_png_to_func(append_bytes, &png, 32, 32, 3, pixels.data(), 32 * 3), 0);
    png.resize(png.size() / 2);
    return png;
}

/// A textured quad with TEXCOORD_0 and TEXCOORD_1.
GltfBuilder textured_quad() {
    GltfBuilder file;
    file.add_triangles({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, {0, 1, 2, 0, 2, 3});
    const std::vector<float> uvs = {0, 0, 1, 0, 1, 1, 0, 1};
    const int texcoords = file.add_accessor(file.add_view(uvs), 5126, 4, "VEC2");
    json& primitive = file.document["meshes"][0]["primitives"][0];
    primitive["attributes"]["TEXCOORD_0"] = texcoords;
    primitive["attributes"]["TEXCOORD_1"] = texcoords;
    primitive["material"] = 0;
    file.document["materials"] = {
        {{"name", "painted"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    file.document["textures"] = {{{"source", 0}}};
    file.document["images"] = {{{"uri", "paint.png"}}};
    return file;
}

/// Writes the level (its buffer as level.bin) and the image beside it; returns the level's path.
std::filesystem::path write_level(const std::filesystem::path& dir, const GltfBuilder& file,
                                  const std::vector<std::uint8_t>& image) {
    json document = file.document;
    document["buffers"] = {{{"byteLength", file.bin.size()}, {"uri", "level.bin"}}};
    std::ofstream(dir / "level.gltf") << document.dump();
    std::ofstream(dir / "level.bin", std::ios::binary)
        .write(reinterpret_cast<const char*>(file.bin.data()),
               static_cast<std::streamsize>(file.bin.size()));
    std::ofstream(dir / "paint.png", std::ios::binary)
        .write(reinterpret_cast<const char*>(image.data()),
               static_cast<std::streamsize>(image.size()));
    return dir / "level.gltf";
}

/// The first error of making the level's instance and its photon world (which reads every
/// material's mean albedo, decoding its texture).
std::string instantiate_error(const std::filesystem::path& level) {
    // The load itself succeeds: only the image's header and the JSON are read there.
    auto scene = std::make_shared<const scene::Scene>(scene::load_gltf(level));
    EXPECT_EQ(scene->source, level.string());
    ecs::Registry registry;
    try {
        (void)world::instantiate(registry, scene);
        ecs::TransformSystem(registry).update();
        lighting::PhotonWorld photons(registry);
        photons.sync();
    } catch (const Error& e) {
        return e.what();
    }
    return "(instantiated)";
}

TEST(InstantiateErrors, AnImageThatDoesNotDecodeNamesTheLevelFile) {
    luxel::testing::TempDir dir;
    const std::filesystem::path level = write_level(dir.path(), textured_quad(), truncated_png());
    const std::string message = instantiate_error(level);
    EXPECT_EQ(message.rfind(level.string() + ": material 0 'painted': base-colour texture: ", 0),
              0u)
        << message;
    EXPECT_NE(message.find("cannot decode PNG"), std::string::npos) << message;
}

TEST(InstantiateErrors, ALightmapTableTheMeshCannotHoldNamesTheLevelFile) {
    luxel::testing::TempDir dir;
    GltfBuilder file = textured_quad();
    file.document["meshes"][0]["primitives"][0].erase("material");
    file.document["nodes"][0]["name"] = "floor";
    // Well-formed, but surface 0 names primitive 7 of a one-primitive mesh.
    file.document["nodes"][0]["extras"] = {{"luxel",
                                            {{"lightmap",
                                              {{"page_size", 16},
                                               {"surfaces",
                                                {{{"id", 0},
                                                  {"primitive", 7},
                                                  {"page", 0},
                                                  {"rect", {1, 1, 14, 14}},
                                                  {"charts", {{0, 0, 16, 16}}},
                                                  {"area", 1.0},
                                                  {"texels", 196}}}},
                                               {"texel_size", 0.25}}}}}};
    const std::filesystem::path level = write_level(dir.path(), file, truncated_png());
    const std::string message = instantiate_error(level);
    EXPECT_EQ(message.rfind(level.string() + ": node 'floor': light-map surface 0", 0), 0u)
        << message;
}

}  // namespace
