#pragma once

// Hand-made glTF files for the hostile-input and mutation tests. Written independently of the
// library's writer so that a bug there cannot hide the same bug in the loader.

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace luxel::testing {

inline std::string to_base64(const std::vector<std::uint8_t>& bytes) {
    static constexpr char kAlphabet[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        std::uint32_t group = static_cast<std::uint32_t>(bytes[i]) << 16;
        const std::size_t have = std::min<std::size_t>(3, bytes.size() - i);
        if (have > 1) {
            group |= static_cast<std::uint32_t>(bytes[i + 1]) << 8;
        }
        if (have > 2) {
            group |= bytes[i + 2];
        }
        for (std::size_t k = 0; k < 4; ++k) {
            out += k <= have ? kAlphabet[(group >> (18 - 6 * k)) & 63] : '=';
        }
    }
    return out;
}

inline void put_u32(std::vector<std::uint8_t>& out, std::uint32_t value) {
    for (int shift = 0; shift < 32; shift += 8) {
        out.push_back(static_cast<std::uint8_t>(value >> shift));
    }
}

inline std::uint32_t get_u32(const std::vector<std::uint8_t>& bytes, std::size_t offset) {
    std::uint32_t value = 0;
    std::memcpy(&value, bytes.data() + offset, 4);
    return value;
}

/// A GLB from JSON text and a binary chunk (omitted when empty).
inline std::vector<std::uint8_t> make_glb(std::string json, std::vector<std::uint8_t> bin) {
    while (json.size() % 4 != 0) {
        json += ' ';
    }
    while (bin.size() % 4 != 0) {
        bin.push_back(0);
    }
    std::vector<std::uint8_t> out;
    const std::size_t total = 12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size());
    put_u32(out, 0x46546C67);
    put_u32(out, 2);
    put_u32(out, static_cast<std::uint32_t>(total));
    put_u32(out, static_cast<std::uint32_t>(json.size()));
    put_u32(out, 0x4E4F534A);
    out.insert(out.end(), json.begin(), json.end());
    if (!bin.empty()) {
        put_u32(out, static_cast<std::uint32_t>(bin.size()));
        put_u32(out, 0x004E4942);
        out.insert(out.end(), bin.begin(), bin.end());
    }
    return out;
}

/// The JSON and BIN chunks of a well-formed GLB (the first two chunks).
struct GlbParts {
    std::string json;
    std::vector<std::uint8_t> bin;
};
inline GlbParts split_glb(const std::vector<std::uint8_t>& glb) {
    GlbParts parts;
    const std::uint32_t json_length = get_u32(glb, 12);
    parts.json.assign(reinterpret_cast<const char*>(glb.data()) + 20, json_length);
    const std::size_t bin_header = 20 + json_length;
    if (glb.size() >= bin_header + 8) {
        const std::uint32_t bin_length = get_u32(glb, bin_header);
        parts.bin.assign(glb.begin() + static_cast<std::ptrdiff_t>(bin_header + 8),
                         glb.begin() + static_cast<std::ptrdiff_t>(bin_header + 8 + bin_length));
    }
    return parts;
}

/// Builds a small glTF document and its buffer by hand.
class GltfBuilder {
  public:
    GltfBuilder() { document["asset"] = {{"version", "2.0"}}; }

    template <typename T>
    int add_view(const std::vector<T>& values) {
        while (bin.size() % 4 != 0) {
            bin.push_back(0);
        }
        const std::size_t offset = bin.size();
        bin.resize(offset + values.size() * sizeof(T));
        std::memcpy(bin.data() + offset, values.data(), values.size() * sizeof(T));
        document["bufferViews"].push_back(
            {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", values.size() * sizeof(T)}});
        return static_cast<int>(document["bufferViews"].size() - 1);
    }

    int add_accessor(int view, int component_type, std::size_t count, const std::string& type,
                     bool normalized = false) {
        nlohmann::json accessor = {{"bufferView", view},
                                   {"componentType", component_type},
                                   {"count", count},
                                   {"type", type}};
        if (normalized) {
            accessor["normalized"] = true;
        }
        document["accessors"].push_back(accessor);
        return static_cast<int>(document["accessors"].size() - 1);
    }

    /// One mesh with one node in the default scene: float positions and, when given,
    /// 32-bit indices.
    void add_triangles(const std::vector<float>& positions,
                       const std::vector<std::uint32_t>& indices) {
        nlohmann::json primitive;
        primitive["attributes"]["POSITION"] =
            add_accessor(add_view(positions), 5126, positions.size() / 3, "VEC3");
        if (!indices.empty()) {
            primitive["indices"] = add_accessor(add_view(indices), 5125, indices.size(), "SCALAR");
        }
        document["meshes"].push_back({{"primitives", {primitive}}});
        document["nodes"].push_back({{"mesh", document["meshes"].size() - 1}});
        document["scenes"] = {{{"nodes", {0}}}};
        document["scene"] = 0;
    }

    /// The document with the buffer as a data URI.
    [[nodiscard]] std::string text() const {
        nlohmann::json out = document;
        if (!bin.empty()) {
            out["buffers"] = {{{"byteLength", bin.size()},
                               {"uri", "data:application/octet-stream;base64," + to_base64(bin)}}};
        }
        return out.dump();
    }

    [[nodiscard]] std::vector<std::uint8_t> glb() const {
        nlohmann::json out = document;
        if (!bin.empty()) {
            out["buffers"] = {{{"byteLength", bin.size()}}};
        }
        return make_glb(out.dump(), bin);
    }

    nlohmann::json document;
    std::vector<std::uint8_t> bin;
};

inline std::vector<std::uint8_t> bytes_of(const std::string& text) {
    return {text.begin(), text.end()};
}

/// The unit triangle in the xy plane.
inline const std::vector<float> kTriangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};

}  // namespace luxel::testing
