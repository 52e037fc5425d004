// Writing an encoded scene to .glb, .gltf + .bin, or .gltf with an embedded buffer.

#include <algorithm>
#include <cctype>

#include "gltf_internal.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/runtime/pending_file.hpp"

namespace luxel::scene {
namespace {

using gltf_detail::EncodedGltf;

std::string dump(const nlohmann::json& document, int indent) {
    // Names set in code may hold invalid UTF-8; replace it rather than throw half-way.
    return document.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

/// A file name as a relative URI: unreserved characters kept, everything else percent-encoded
/// (the loader decodes it again).
std::string uri_for_file_name(const std::string& name) {
    static constexpr char kHex[] = "0123456789ABCDEF";
    std::string uri;
    for (const char c : name) {
        const auto byte = static_cast<unsigned char>(c);
        if (std::isalnum(byte) != 0 || c == '-' || c == '_' || c == '.' || c == '~') {
            uri += c;
        } else {
            uri += '%';
            uri += kHex[byte >> 4];
            uri += kHex[byte & 15];
        }
    }
    return uri;
}

void write_file(const std::filesystem::path& file, const void* data, std::size_t size) {
    // Whole or not at all: an interrupted save leaves the previous file in place.
    write_file_atomically(file, {static_cast<const std::byte*>(data), size});
}

EncodedGltf encode_validated(const Scene& scene, const std::string& display_name) {
    try {
        scene.validate();
    } catch (const Error& e) {
        throw Error(display_name + ": cannot save: " + e.what());
    }
    return gltf_detail::encode_scene(scene);
}

void embed_buffer(EncodedGltf& encoded) {
    if (!encoded.bin.empty()) {
        encoded.document["buffers"][0]["uri"] =
            "data:application/octet-stream;base64," + gltf_detail::base64_encode(encoded.bin);
    }
}

}  // namespace

void save_gltf(const Scene& scene, const std::filesystem::path& file, const SaveOptions& options) {
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (extension != ".glb" && extension != ".gltf") {
        throw Error(file.string() + ": cannot save: the extension must be .glb or .gltf");
    }
    EncodedGltf encoded = encode_validated(scene, file.string());
    if (extension == ".glb") {
        const std::vector<std::uint8_t> glb =
            gltf_detail::build_glb(dump(encoded.document, -1), encoded.bin);
        write_file(file, glb.data(), glb.size());
        return;
    }
    if (options.embed_buffers) {
        embed_buffer(encoded);
    } else if (!encoded.bin.empty()) {
        std::filesystem::path bin_file = file;
        bin_file.replace_extension(".bin");
        write_file(bin_file, encoded.bin.data(), encoded.bin.size());
        encoded.document["buffers"][0]["uri"] = uri_for_file_name(bin_file.filename().string());
    }
    const std::string text = dump(encoded.document, 2) + "\n";
    write_file(file, text.data(), text.size());
}

std::vector<std::uint8_t> save_gltf_to_memory(const Scene& scene, GltfContainer container) {
    EncodedGltf encoded = encode_validated(scene, "glTF in memory");
    if (container == GltfContainer::Binary) {
        return gltf_detail::build_glb(dump(encoded.document, -1), encoded.bin);
    }
    embed_buffer(encoded);
    const std::string text = dump(encoded.document, 2) + "\n";
    return {text.begin(), text.end()};
}

}  // namespace luxel::scene
