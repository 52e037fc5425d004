// Writes the fuzzing seed corpus: the mutation test's scenes as .glb and as .gltf with an
// embedded buffer.
//   luxel_gltf_fuzz_seeds DIR

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "luxel/scene/gltf.hpp"
#include "test_scenes.hpp"

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: luxel_gltf_fuzz_seeds DIR\n");
        return 2;
    }
    const std::filesystem::path dir(argv[1]);
    std::filesystem::create_directories(dir);
    int written = 0;
    for (const auto& [name, scene] : luxel::testing::mutation_seed_scenes()) {
        for (const auto container :
             {luxel::scene::GltfContainer::Binary, luxel::scene::GltfContainer::EmbeddedText}) {
            const auto bytes = luxel::scene::save_gltf_to_memory(scene, container);
            const char* extension =
                container == luxel::scene::GltfContainer::Binary ? ".glb" : ".gltf";
            std::ofstream out(dir / (name + extension), std::ios::binary);
            out.write(reinterpret_cast<const char*>(bytes.data()),
                      static_cast<std::streamsize>(bytes.size()));
            if (!out) {
                std::fprintf(stderr, "cannot write %s\n", (dir / (name + extension)).c_str());
                return 1;
            }
            ++written;
        }
    }
    std::printf("wrote %d seeds to %s\n", written, dir.c_str());
    return 0;
}
