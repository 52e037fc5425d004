#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/scene/scene.hpp"

/// What a loaded level lacks that a user would otherwise only notice as a black frame, an
/// arbitrary view or missing indirect light. luxel-sandbox, luxel-ref and luxel-bench all check
/// a level here and print the same words, so one level gets one diagnosis whichever program
/// runs it.
namespace luxel::scene {

/// The view a program shows of a level that has no camera: from (0, 1, 3) towards (0, 1, 0),
/// eye height over a floor at y = 0, looking down -z as a glTF camera without a transform does.
struct DefaultView {
    glm::vec3 eye{0.0f, 1.0f, 3.0f};
    glm::vec3 target{0.0f, 1.0f, 0.0f};
    float vertical_fov_degrees = 60.0f;
};

/// "from (0, 1, 3) looking at (0, 1, 0), vertical field of view 60 degrees"
[[nodiscard]] std::string describe(const DefaultView& view);

enum class LevelProblem : std::uint8_t {
    NoLight,      ///< no punctual light and no emissive material: every frame is black
    NoCamera,     ///< the default view is used
    NotPrepared,  ///< no light-map layout from luxel-prep: no indirect light
};

struct LevelDiagnosis {
    LevelProblem problem = LevelProblem::NoLight;
    std::string message;  ///< one line, starting with the level's file
};

struct LevelCheckOptions {
    /// Whether the program shows the level through its camera. luxel-ref given --camera, or
    /// asked for light maps only, does not, and is not told the level has none.
    bool uses_camera = true;
};

/// A light on some node, or a material that emits on some mesh node's primitive.
[[nodiscard]] bool has_light_or_emission(const Scene& scene);
/// A node with a camera.
[[nodiscard]] bool has_camera(const Scene& scene);
/// Whether luxel-prep has written its light-map layout into the level: false when some mesh
/// node has a primitive luxel-prep would light-map (triangles, not a mirror or glass) and no
/// node carries `extras.luxel.lightmap`. A level with nothing to light-map counts as prepared.
[[nodiscard]] bool is_prepared(const Scene& scene);

/// Where `luxel-prep` writes the prepared copy of `file`: beside it, `NAME-prepared.glb`.
[[nodiscard]] std::filesystem::path prepared_path(const std::filesystem::path& file);
/// The command that prepares `file`: `luxel-prep FILE -o NAME-prepared.glb` (paths quoted for a
/// POSIX shell where they need it).
[[nodiscard]] std::string prep_command(const std::filesystem::path& file);

/// "FILE: not prepared for light maps (luxel-prep has not written its light-map layout into
/// it)": how every message about an unprepared level begins.
[[nodiscard]] std::string not_prepared_text(const Scene& scene);

/// Every problem of `scene`, each as one line naming `scene.source` (the level's file).
[[nodiscard]] std::vector<LevelDiagnosis> check_level(const Scene& scene,
                                                      const LevelCheckOptions& options = {});
/// The one diagnosis of `problem` for `scene` (the words check_level uses), whether or not the
/// scene has the problem: for callers that say it in another form, such as an error.
[[nodiscard]] std::string diagnosis_text(const Scene& scene, LevelProblem problem);

/// Writes each diagnosis as one warning line through luxel::log.
void warn(const std::vector<LevelDiagnosis>& diagnoses);

}  // namespace luxel::scene
