// luxel-make-levels: writes the built-in levels as .glb files.
//   luxel-make-levels [--out DIR] [--level NAME]... [--list]
// The committed files under assets/levels/ are this program's output; rebuild them with
//   build/bin/luxel-make-levels --out assets/levels

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <string>
#include <system_error>
#include <vector>

#include <CLI/CLI.hpp>

#include "levels.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/runtime/scene/gltf.hpp"

int main(int argc, char** argv) {
    CLI::App app{"Writes luxel's built-in levels as glTF binary (.glb) files."};
    std::filesystem::path out = "assets/levels";
    std::vector<std::string> only;
    bool list = false;
    app.add_option("--out", out, "output directory")->capture_default_str();
    app.add_option("--level", only, "write only these levels (repeatable)");
    app.add_flag("--list", list, "list the levels and exit");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }
    const auto recipes = luxel::levels::built_in_levels();
    if (list) {
        for (const auto& recipe : recipes) {
            std::cout << recipe.name << "\t" << recipe.description << "\n";
        }
        return 0;
    }
    for (const auto& name : only) {
        bool known = false;
        for (const auto& recipe : recipes) {
            known = known || recipe.name == name;
        }
        if (!known) {
            std::cerr << "luxel-make-levels: unknown level '" << name << "' (see --list)\n";
            return 1;
        }
    }
    std::error_code directory_error;
    std::filesystem::create_directories(out, directory_error);
    if (directory_error) {
        std::cerr << "luxel-make-levels: cannot create " << out.string() << ": "
                  << directory_error.message() << "\n";
        return 1;
    }
    try {
        for (const auto& recipe : recipes) {
            if (!only.empty() && std::find(only.begin(), only.end(), recipe.name) == only.end()) {
                continue;
            }
            const luxel::scene::Scene scene = recipe.build();
            const auto file = out / (recipe.name + ".glb");
            luxel::scene::save_gltf(scene, file);
            std::cout << file.string() << ": " << scene.nodes.size() << " nodes, "
                      << scene.triangle_count() << " triangles, " << scene.lights.size()
                      << " lights, " << scene.animations.size() << " animations\n";
        }
    } catch (const luxel::Error& e) {
        std::cerr << "luxel-make-levels: error: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
