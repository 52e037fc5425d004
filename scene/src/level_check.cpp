#include "luxel/scene/level_check.hpp"

#include <algorithm>
#include <cstdio>

#include "luxel/runtime/log.hpp"
#include "luxel/scene/portal.hpp"

namespace luxel::scene {
namespace {

std::string number(float value) {
    char text[32];
    std::snprintf(text, sizeof(text), "%g", static_cast<double>(value));
    return text;
}

std::string point(const glm::vec3& p) {
    return "(" + number(p.x) + ", " + number(p.y) + ", " + number(p.z) + ")";
}

/// `text` as one word for a POSIX shell: unchanged when it holds only characters no shell
/// treats specially, else in single quotes (a quote inside as '\'').
std::string shell_word(const std::string& text) {
    const bool plain = !text.empty() && std::all_of(text.begin(), text.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
               std::string_view("_-./+=:,@%").find(c) != std::string_view::npos;
    });
    if (plain) {
        return text;
    }
    std::string quoted = "'";
    for (char c : text) {
        quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    }
    return quoted + "'";
}

/// What luxel-prep light-maps: triangles of any material but a mirror or glass (see
/// tools/prep's is_lightmapped with lightmap_specular off).
bool lightmappable(const Scene& scene, const Primitive& primitive) {
    if (primitive.indices.empty()) {
        return false;
    }
    return primitive.material < 0 ||
           !scene.materials.at(static_cast<std::size_t>(primitive.material)).is_specular();
}

}  // namespace

std::string describe(const DefaultView& view) {
    return "from " + point(view.eye) + " looking at " + point(view.target) +
           ", vertical field of view " + number(view.vertical_fov_degrees) + " degrees";
}

bool has_light_or_emission(const Scene& scene) {
    for (const Node& node : scene.nodes) {
        if (node.light >= 0) {
            return true;
        }
        if (node.mesh < 0) {
            continue;
        }
        for (const Primitive& primitive :
             scene.meshes.at(static_cast<std::size_t>(node.mesh)).primitives) {
            if (primitive.material >= 0 &&
                scene.materials.at(static_cast<std::size_t>(primitive.material)).is_emissive()) {
                return true;
            }
        }
    }
    return false;
}

bool has_camera(const Scene& scene) {
    return std::any_of(scene.nodes.begin(), scene.nodes.end(),
                       [](const Node& node) { return node.camera >= 0; });
}

bool is_prepared(const Scene& scene) {
    bool needs_layout = false;
    for (const Node& node : scene.nodes) {
        if (node.flags.raw.is_object() && node.flags.raw.contains("lightmap")) {
            return true;
        }
        if (node.mesh < 0 || is_portal(node)) {
            continue;
        }
        const Mesh& mesh = scene.meshes.at(static_cast<std::size_t>(node.mesh));
        needs_layout = needs_layout || std::any_of(mesh.primitives.begin(), mesh.primitives.end(),
                                                   [&](const Primitive& primitive) {
                                                       return lightmappable(scene, primitive);
                                                   });
    }
    return !needs_layout;
}

std::filesystem::path prepared_path(const std::filesystem::path& file) {
    return file.parent_path() / (file.stem().string() + "-prepared.glb");
}

std::string prep_command(const std::filesystem::path& file) {
    return "luxel-prep " + shell_word(file.string()) + " -o " +
           shell_word(prepared_path(file).string());
}

std::string not_prepared_text(const Scene& scene) {
    return scene.in_file(
        "not prepared for light maps (luxel-prep has not written its light-map layout into it)");
}

std::string diagnosis_text(const Scene& scene, LevelProblem problem) {
    switch (problem) {
        case LevelProblem::NoLight:
            return scene.in_file(
                "no light and no emissive material: every frame will be black (add a "
                "KHR_lights_punctual light or a material with an emissiveFactor)");
        case LevelProblem::NoCamera:
            return scene.in_file("no camera: using the default view " + describe(DefaultView{}));
        case LevelProblem::NotPrepared:
            return not_prepared_text(scene) +
                   ": it gets no indirect light; prepare it with: " + prep_command(scene.source);
    }
    return scene.in_file("unknown problem");
}

std::vector<LevelDiagnosis> check_level(const Scene& scene, const LevelCheckOptions& options) {
    std::vector<LevelDiagnosis> found;
    auto add = [&](LevelProblem problem) {
        found.push_back({problem, diagnosis_text(scene, problem)});
    };
    if (!has_light_or_emission(scene)) {
        add(LevelProblem::NoLight);
    }
    if (options.uses_camera && !has_camera(scene)) {
        add(LevelProblem::NoCamera);
    }
    if (!is_prepared(scene)) {
        add(LevelProblem::NotPrepared);
    }
    return found;
}

void warn(const std::vector<LevelDiagnosis>& diagnoses) {
    for (const LevelDiagnosis& diagnosis : diagnoses) {
        log::warn(diagnosis.message);
    }
}

}  // namespace luxel::scene
