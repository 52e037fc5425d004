// glTF loading: reads the file, checks the container and JSON before tinygltf parses them,
// confines tinygltf's file access to the asset's directory, keeps images encoded, and then
// converts the parsed model into a Scene (gltf_import_*.cpp) with every reference checked.

#include <algorithm>
#include <array>
#include <fstream>
#include <limits>
#include <new>
#include <string_view>
#include <system_error>

#include <tiny_gltf.h>

#include "gltf_internal.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/runtime/log.hpp"
#include "luxel/scene/sky.hpp"

namespace luxel::scene {
namespace gltf_detail {

void ImportContext::fail(const std::string& problem) const {
    throw Error(display_name_ + ": " + problem);
}

void ImportContext::warn(const std::string& message) const {
    log::debug(display_name_, ": ", message);
    scene_.report.warnings.push_back(message);
}

void ImportContext::count_triangles(std::uint64_t triangles, const std::string& where) {
    triangles_ += triangles;
    if (triangles_ > options_.max_total_triangles) {
        fail(where + ": the scene exceeds the limit of " +
             std::to_string(options_.max_total_triangles) + " triangles");
    }
}

std::string label(const char* kind, std::size_t index, const std::string& name) {
    std::string text = std::string(kind) + " " + std::to_string(index);
    if (!name.empty()) {
        text += " '" + name + "'";
    }
    return text;
}

nlohmann::json parse_kept_json(const std::string& text) {
    if (text.empty()) {
        return nlohmann::json::object();
    }
    // tinygltf produced this text by dumping an already parsed value, so it parses; the
    // non-throwing form still keeps a surprise from escaping as a non-luxel exception.
    nlohmann::json value = nlohmann::json::parse(text, nullptr, false);
    return value.is_discarded() ? nlohmann::json::object() : value;
}

}  // namespace gltf_detail

namespace {

using gltf_detail::ImportContext;

/// The extensions luxel reads; a file may require only these.
constexpr std::array<std::string_view, 5> kSupportedRequiredExtensions = {
    "KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_materials_transmission",
    "KHR_materials_ior", "KHR_materials_volume"};

/// What tinygltf's file callbacks may touch: regular files inside the asset's directory, each
/// and all together within the limits.
struct ExternalFiles {
    std::filesystem::path base_dir;       ///< absolute and normal; empty: no external files at all
    std::filesystem::path real_base_dir;  ///< base_dir with every symbolic link resolved
    const LoadOptions* options = nullptr;
    std::uint64_t bytes_read = 0;
    std::vector<std::filesystem::path> read;  ///< real paths of the files read, in order
    std::vector<std::string> refusals;        ///< why a file was refused, for the error message

    /// The file's real path if it lies inside base_dir and is a regular file; empty (and a
    /// refusal recorded) otherwise. Both checks look at the path as written and at the real
    /// path with every symbolic link resolved: a link inside the level's folder that points
    /// out of it is refused like a "../" (docs/LEVELS.md, "Files a level may read").
    std::filesystem::path admit(const std::string& requested) {
        if (base_dir.empty()) {
            refusals.push_back("'" + requested +
                               "' is an external file, but no directory was given to read it from");
            return {};
        }
        std::error_code error;
        const std::filesystem::path absolute =
            std::filesystem::absolute(std::filesystem::path(requested), error).lexically_normal();
        const std::filesystem::path relative = absolute.lexically_relative(base_dir);
        if (error || relative.empty() || *relative.begin() == "..") {
            refusals.push_back("'" + requested + "' lies outside the file's directory");
            return {};
        }
        if (!std::filesystem::is_regular_file(absolute, error)) {
            refusals.push_back("'" + absolute.string() + "' does not exist or is not a file");
            return {};
        }
        if (real_base_dir.empty()) {
            refusals.push_back("'" + requested + "': the file's directory " + base_dir.string() +
                               " cannot be resolved");
            return {};
        }
        const std::filesystem::path real = std::filesystem::canonical(absolute, error);
        const std::filesystem::path real_relative =
            error ? std::filesystem::path() : real.lexically_relative(real_base_dir);
        if (real_relative.empty() || *real_relative.begin() == "..") {
            refusals.push_back("'" + requested +
                               "' is a symbolic link to a file outside the file's directory");
            return {};
        }
        return real;  // what gets opened: the path that was checked, with no link left in it
    }
};

/// The real path of a sky map a level names in its extras (relative to its folder), admitted
/// by the same rules as its buffers and images and within the file-size limit; an Error naming
/// the field and the reason otherwise. The map itself is read later (world::make_sky_radiance,
/// which checks its header before any pixel memory).
std::filesystem::path admit_sky_map(ExternalFiles& files, const std::filesystem::path& written,
                                    const std::string& display_name) {
    const std::string field =
        display_name + ": extras.luxel.sky.file '" + written.generic_string() + "'";
    const std::filesystem::path admitted = files.admit((files.base_dir / written).string());
    if (admitted.empty()) {
        throw Error(field + ": " + files.refusals.back());
    }
    std::error_code error;
    const std::uint64_t size = std::filesystem::file_size(admitted, error);
    if (error || size > files.options->max_file_size) {
        throw Error(field + ": " +
                    (error ? "cannot read: " + error.message()
                           : std::to_string(size) + " bytes, more than the limit of " +
                                 std::to_string(files.options->max_file_size)));
    }
    return admitted;
}

bool file_exists(const std::string& path, void* user) {
    return !static_cast<ExternalFiles*>(user)->admit(path).empty();
}

std::string expand_file_path(const std::string& path, void* /*user*/) {
    // tinygltf's default runs wordexp() (shell expansion) on names from the file; names are
    // taken literally here.
    return path;
}

bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                     void* user) {
    try {
        ExternalFiles& files = *static_cast<ExternalFiles*>(user);
        const std::filesystem::path admitted = files.admit(path);
        if (admitted.empty()) {
            *err = files.refusals.back();
            return false;
        }
        std::error_code error;
        const std::uint64_t size = std::filesystem::file_size(admitted, error);
        if (error) {
            *err = "cannot read '" + admitted.string() + "': " + error.message();
            return false;
        }
        if (size > files.options->max_file_size ||
            files.bytes_read + size > files.options->max_external_bytes) {
            *err = "'" + admitted.string() + "' (" + std::to_string(size) +
                   " bytes) exceeds the size limit";
            files.refusals.push_back(*err);
            return false;
        }
        std::ifstream stream(admitted, std::ios::binary);
        out->resize(static_cast<std::size_t>(size));
        stream.read(reinterpret_cast<char*>(out->data()), static_cast<std::streamsize>(size));
        if (!stream || static_cast<std::uint64_t>(stream.gcount()) != size) {
            *err = "cannot read '" + admitted.string() + "'";
            return false;
        }
        files.bytes_read += size;
        files.read.push_back(admitted);
        return true;
    } catch (const std::exception& e) {  // nothing may unwind through tinygltf's C-style API
        *err = e.what();
        return false;
    }
}

bool refuse_write(std::string* err, const std::string& /*path*/,
                  const std::vector<unsigned char>& /*contents*/, void* /*user*/) {
    *err = "the loader writes no files";
    return false;
}

/// tinygltf image callback: keeps the encoded bytes (no decoding), after checking that an
/// image stored in a bufferView lies inside its buffer (tinygltf does not check that).
bool keep_encoded_image(tinygltf::Image* image, const int image_index, std::string* err,
                        std::string* /*warn*/, int /*width*/, int /*height*/,
                        const unsigned char* bytes, int size, void* user) {
    try {
        const auto& model = *static_cast<const tinygltf::Model*>(user);
        image->as_is = true;
        if (image->bufferView < 0) {
            if (bytes == nullptr || size <= 0) {
                *err = "image " + std::to_string(image_index) + " is empty";
                return false;
            }
            image->image.assign(bytes, bytes + size);
            return true;
        }
        // tinygltf checked the bufferView and buffer indices, not the byte range.
        const tinygltf::BufferView& view =
            model.bufferViews[static_cast<std::size_t>(image->bufferView)];
        const std::vector<unsigned char>& buffer =
            model.buffers[static_cast<std::size_t>(view.buffer)].data;
        if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset ||
            view.byteLength == 0) {
            *err = "image " + std::to_string(image_index) + ": bufferView " +
                   std::to_string(image->bufferView) + " (byteOffset " +
                   std::to_string(view.byteOffset) + ", byteLength " +
                   std::to_string(view.byteLength) + ") does not lie inside buffer " +
                   std::to_string(view.buffer) + " (" + std::to_string(buffer.size()) + " bytes)";
            return false;
        }
        const auto first = buffer.begin() + static_cast<std::ptrdiff_t>(view.byteOffset);
        image->image.assign(first, first + static_cast<std::ptrdiff_t>(view.byteLength));
        return true;
    } catch (const std::exception& e) {
        *err = e.what();
        return false;
    }
}

std::string trimmed(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) {
        text.pop_back();
    }
    // tinygltf separates several messages with newlines; one line reads better after the path.
    std::replace(text.begin(), text.end(), '\n', ';');
    return text;
}

void check_required_extensions(const tinygltf::Model& model, const ImportContext& context) {
    for (const std::string& extension : model.extensionsRequired) {
        if (std::find(kSupportedRequiredExtensions.begin(), kSupportedRequiredExtensions.end(),
                      extension) == kSupportedRequiredExtensions.end()) {
            context.fail("requires the extension '" + extension +
                         "', which luxel does not support");
        }
    }
}

/// The scene's extras.luxel.sky, if it has one (docs/LEVELS.md, "Sky").
void read_scene_sky(ImportContext& context, const tinygltf::Scene& source, int index) {
    const nlohmann::json extras = gltf_detail::parse_kept_json(source.extras_json_string);
    if (!extras.is_object()) {
        return;
    }
    const auto luxel = extras.find("luxel");
    if (luxel == extras.end() || !luxel->is_object()) {
        return;
    }
    const auto sky = luxel->find("sky");
    if (sky == luxel->end()) {
        return;
    }
    try {
        context.scene().sky = read_sky_extras(*sky);
    } catch (const Error& e) {
        context.fail("scene " + std::to_string(index) + ": " + e.what());
    }
}

void collect_roots(ImportContext& context) {
    const tinygltf::Model& model = context.model();
    Scene& scene = context.scene();
    if (model.scenes.empty()) {
        // No scene: every parentless node is a root, so the file still shows something.
        for (std::size_t i = 0; i < scene.nodes.size(); ++i) {
            if (scene.nodes[i].parent < 0) {
                scene.roots.push_back(static_cast<int>(i));
            }
        }
        return;
    }
    int chosen = model.defaultScene;
    if (chosen == -1) {
        chosen = 0;
    }
    if (chosen < 0 || static_cast<std::size_t>(chosen) >= model.scenes.size()) {
        context.fail("default scene " + std::to_string(chosen) + " out of range (" +
                     std::to_string(model.scenes.size()) + " scenes)");
    }
    const tinygltf::Scene& source = model.scenes[static_cast<std::size_t>(chosen)];
    scene.name = source.name;
    read_scene_sky(context, source, chosen);
    for (const int root : source.nodes) {
        if (root < 0 || static_cast<std::size_t>(root) >= scene.nodes.size()) {
            context.fail("scene " + std::to_string(chosen) + ": node " + std::to_string(root) +
                         " out of range");
        }
        if (scene.nodes[static_cast<std::size_t>(root)].parent != -1) {
            context.fail("scene " + std::to_string(chosen) + ": node " + std::to_string(root) +
                         " is listed as a root but has a parent");
        }
        if (std::find(scene.roots.begin(), scene.roots.end(), root) != scene.roots.end()) {
            context.fail("scene " + std::to_string(chosen) + ": node " + std::to_string(root) +
                         " is listed twice");
        }
        scene.roots.push_back(root);
    }
}

Scene load(std::span<const std::uint8_t> bytes, const std::string& display_name,
           const std::filesystem::path& base_dir, const LoadOptions& options) {
    const auto fail = [&display_name](const std::string& problem) -> void {
        throw Error(display_name + ": " + problem);
    };
    if (bytes.empty()) {
        fail("the file is empty");
    }
    if (bytes.size() > options.max_file_size) {
        fail("the file is " + std::to_string(bytes.size()) + " bytes, more than the limit of " +
             std::to_string(options.max_file_size));
    }

    // The container and the JSON are checked here first: tinygltf trusts the GLB chunk
    // lengths too far and recurses into nested JSON without a bound.
    std::span<const std::uint8_t> json = bytes;
    std::span<const std::uint8_t> glb_for_tinygltf;
    std::vector<std::uint8_t> rebuilt_glb;
    const bool binary = gltf_detail::has_glb_magic(bytes);
    if (binary) {
        std::string problem;
        const gltf_detail::GlbLayout layout = gltf_detail::parse_glb(bytes, problem);
        if (!problem.empty()) {
            fail(problem);
        }
        json = layout.json;
        glb_for_tinygltf = bytes;
        if (layout.bin.empty() && layout.declared_length != 20 + layout.json.size()) {
            // Only unknown chunks follow the JSON; tinygltf would take the first for BIN.
            rebuilt_glb = gltf_detail::build_glb(
                std::string(reinterpret_cast<const char*>(json.data()), json.size()), {});
            glb_for_tinygltf = rebuilt_glb;
        }
    }
    if (const std::string problem = gltf_detail::check_json(json, options); !problem.empty()) {
        fail(problem);
    }

    ExternalFiles files;
    files.options = &options;
    if (!base_dir.empty()) {
        std::error_code error;
        files.base_dir = std::filesystem::absolute(base_dir, error).lexically_normal();
        // A folder that cannot be resolved (gone, or given for a file loaded from memory) lets
        // no external file in; a level with everything embedded still loads.
        files.real_base_dir = std::filesystem::canonical(files.base_dir, error);
    }
    tinygltf::Model model;
    tinygltf::TinyGLTF parser;
    parser.SetFsCallbacks(
        {&file_exists, &expand_file_path, &read_whole_file, &refuse_write, &files});
    parser.SetImageLoader(&keep_encoded_image, &model);
    // The raw text of `extras` and `extensions` is what luxel reads them from: tinygltf's own
    // Value drops empty objects and truncates 64-bit integers.
    parser.SetStoreOriginalJSONForExtrasAndExtensions(true);

    std::string error;
    std::string warning;
    bool parsed = false;
    try {
        // Every length handed over fits: the file is below max_file_size and GLB lengths are
        // 32-bit by format.
        if (bytes.size() > std::numeric_limits<unsigned int>::max()) {
            fail("the file is larger than 4 GiB");
        }
        const std::string base = files.base_dir.string();
        parsed = binary ? parser.LoadBinaryFromMemory(
                              &model, &error, &warning, glb_for_tinygltf.data(),
                              static_cast<unsigned int>(glb_for_tinygltf.size()), base)
                        : parser.LoadASCIIFromString(&model, &error, &warning,
                                                     reinterpret_cast<const char*>(json.data()),
                                                     static_cast<unsigned int>(json.size()), base);
    } catch (const std::bad_alloc&) {
        fail("out of memory while parsing");
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        fail(std::string("invalid glTF: ") + e.what());
    }
    if (!parsed) {
        std::string message = "invalid glTF: " + trimmed(error.empty() ? warning : error);
        for (const std::string& refusal : files.refusals) {
            message += "; " + refusal;
        }
        fail(message);
    }

    Scene scene;
    scene.source = display_name;
    scene.report.external_files = std::move(files.read);
    ImportContext context(model, display_name, options, scene);
    if (!warning.empty()) {
        context.warn(trimmed(warning));
    }
    check_required_extensions(model, context);
    try {
        gltf_detail::import_materials(context);
        gltf_detail::import_meshes(context);
        gltf_detail::import_lights(context);
        gltf_detail::import_cameras(context);
        gltf_detail::import_nodes(context);
        gltf_detail::check_combined_limits(context);
        collect_roots(context);
        gltf_detail::import_animations(context);
        gltf_detail::import_skins(context);
    } catch (const std::bad_alloc&) {
        fail("out of memory while reading the scene");
    }
    if (scene.sky.kind == SkySpec::Kind::Map) {
        scene.sky.map = admit_sky_map(files, scene.sky.map, display_name);
        scene.report.external_files.push_back(scene.sky.map);
    }
    try {
        scene.validate();
    } catch (const Error& e) {
        // The importer checks all of this itself; reaching here is a luxel bug, still
        // reported against the file rather than crashing on it later.
        fail(e.what());
    }
    if (!scene.report.warnings.empty()) {
        log::warn(display_name, ": loaded with ", scene.report.warnings.size(),
                  " warning(s), first: ", scene.report.warnings.front());
    }
    return scene;
}

}  // namespace

Scene load_gltf(const std::filesystem::path& file, const LoadOptions& options) {
    const std::string display_name = file.string();
    std::error_code error;
    const auto status = std::filesystem::status(file, error);
    if (error || !std::filesystem::exists(status)) {
        throw Error(display_name + ": cannot open: no such file");
    }
    if (!std::filesystem::is_regular_file(status)) {
        throw Error(display_name + ": cannot open: not a regular file");
    }
    const std::uint64_t size = std::filesystem::file_size(file, error);
    if (error) {
        throw Error(display_name + ": cannot read: " + error.message());
    }
    if (size > options.max_file_size) {
        throw Error(display_name + ": the file is " + std::to_string(size) +
                    " bytes, more than the limit of " + std::to_string(options.max_file_size));
    }
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
    std::ifstream stream(file, std::ios::binary);
    stream.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size));
    if (!stream || static_cast<std::uint64_t>(stream.gcount()) != size) {
        throw Error(display_name + ": cannot read the file");
    }
    std::filesystem::path base_dir = file.parent_path();
    if (base_dir.empty()) {
        base_dir = ".";
    }
    return load(bytes, display_name, base_dir, options);
}

Scene load_gltf_from_memory(std::span<const std::uint8_t> bytes, const std::string& display_name,
                            const std::filesystem::path& base_dir, const LoadOptions& options) {
    return load(bytes, display_name, base_dir, options);
}

}  // namespace luxel::scene
