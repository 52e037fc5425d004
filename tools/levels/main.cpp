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
#include "luxel/runtime/cli.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/runtime/tool_main.hpp"
#include "luxel/scene/gltf.hpp"

namespace {

int run(int argc, char** argv) {
    CLI::App app{"Writes luxel's built-in levels as glTF binary (.glb) files."};
    std::filesystem::path out = "assets/levels";
    std::vector<std::string> only;
    bool list = false;
    const auto recipes = luxel::levels::built_in_levels();
    std::vector<std::string> names;
    for (const auto& recipe : recipes) {
        names.push_back(recipe.name);
    }
    app.add_option("--out", out, "output directory")->capture_default_str();
    app.add_option("--level", only, "write only these levels (repeatable; see --list)")
        ->check(CLI::IsMember(names));
    app.add_flag("--list", list, "list the levels and exit");
    if (!luxel::cli::parse(app, argc, argv)) {
        return 0;
    }
    if (list) {
        for (const auto& recipe : recipes) {
            std::cout << recipe.name << "\t" << recipe.description << "\n";
        }
        return 0;
    }
    std::error_code directory_error;
    std::filesystem::create_directories(out, directory_error);
    if (directory_error) {
        throw luxel::Error("--out " + out.string() +
                           ": cannot create the folder: " + directory_error.message());
    }
    for (const auto& recipe : recipes) {
        if (!only.empty() && std::find(only.begin(), only.end(), recipe.name) == only.end()) {
            continue;
        }
        const luxel::scene::Scene scene = recipe.build();
        const auto file = out / (recipe.name + ".glb");
        luxel::scene::save_gltf(scene, file);
        std::cout << file.string() << ": " << scene.nodes.size() << " nodes, "
                  << scene.triangle_count() << " triangles, " << scene.lights.size() << " lights, "
                  << scene.animations.size() << " animations\n";
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return luxel::run_tool("luxel-make-levels", run, argc, argv);
}
