// The GLB container (reading and writing its chunk table) and base64 for embedded buffers.
// The JSON pre-check is in gltf_json_check.cpp.

#include <algorithm>
#include <cstring>
#include <iterator>

#include "gltf_internal.hpp"

namespace luxel::scene::gltf_detail {
namespace {

std::uint32_t read_u32(std::span<const std::uint8_t> bytes, std::size_t offset) {
    // GLB is little-endian, like every machine luxel runs on; assemble bytes anyway so the
    // code says what the format is.
    return static_cast<std::uint32_t>(bytes[offset]) |
           (static_cast<std::uint32_t>(bytes[offset + 1]) << 8) |
           (static_cast<std::uint32_t>(bytes[offset + 2]) << 16) |
           (static_cast<std::uint32_t>(bytes[offset + 3]) << 24);
}

void append_u32(std::vector<std::uint8_t>& out, std::uint32_t value) {
    for (int shift = 0; shift < 32; shift += 8) {
        out.push_back(static_cast<std::uint8_t>(value >> shift));
    }
}

std::string chunk_type_name(std::uint32_t type) {
    std::string name;
    for (int shift = 0; shift < 32; shift += 8) {
        const auto c = static_cast<char>((type >> shift) & 0xFF);
        name += (c >= 0x20 && c < 0x7F) ? c : '?';
    }
    return name;
}

}  // namespace

bool has_glb_magic(std::span<const std::uint8_t> bytes) {
    // A file cut inside the magic itself still reads as a (truncated) GLB.
    static constexpr std::uint8_t kMagic[4] = {'g', 'l', 'T', 'F'};
    const std::size_t n = std::min<std::size_t>(bytes.size(), 4);
    return n > 0 && std::equal(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(n),
                               std::begin(kMagic));
}

GlbLayout parse_glb(std::span<const std::uint8_t> bytes, std::string& problem) {
    const std::uint64_t size = bytes.size();
    if (size < 12) {
        problem = "truncated GLB: " + std::to_string(size) + " bytes, the header alone needs 12";
        return {};
    }
    const std::uint32_t version = read_u32(bytes, 4);
    if (version != 2) {
        problem = "GLB version " + std::to_string(version) + " is not supported (only 2)";
        return {};
    }
    const std::uint32_t length = read_u32(bytes, 8);
    if (length > size) {
        problem = "truncated GLB: the header says " + std::to_string(length) + " bytes but only " +
                  std::to_string(size) + " are present";
        return {};
    }
    if (length < size) {
        problem = "GLB header says " + std::to_string(length) + " bytes but the data holds " +
                  std::to_string(size);
        return {};
    }

    GlbLayout layout;
    layout.declared_length = length;
    std::uint64_t offset = 12;
    for (int chunk = 0; offset < length; ++chunk) {
        if (offset + 8 > length) {
            problem = "truncated GLB: chunk " + std::to_string(chunk) + " header cut off";
            return {};
        }
        const std::uint32_t chunk_length = read_u32(bytes, offset);
        const std::uint32_t chunk_type = read_u32(bytes, offset + 4);
        const std::uint64_t data_begin = offset + 8;
        // 64-bit sums: a 32-bit chunk length near 4 GiB cannot wrap past the end.
        if (data_begin + chunk_length > length) {
            problem = "truncated GLB: chunk " + std::to_string(chunk) + " (" +
                      chunk_type_name(chunk_type) + ") claims " + std::to_string(chunk_length) +
                      " bytes but only " + std::to_string(length - data_begin) + " remain";
            return {};
        }
        if (chunk_length % 4 != 0) {
            problem = "GLB chunk " + std::to_string(chunk) + " length " +
                      std::to_string(chunk_length) + " is not a multiple of 4";
            return {};
        }
        const auto data = bytes.subspan(static_cast<std::size_t>(data_begin), chunk_length);
        if (chunk == 0) {
            if (chunk_type != kGlbJsonChunk || chunk_length == 0) {
                problem = "GLB's first chunk must be a non-empty JSON chunk, found " +
                          chunk_type_name(chunk_type);
                return {};
            }
            layout.json = data;
        } else if (chunk == 1 && chunk_type == kGlbBinChunk) {
            layout.bin = data;
        } else if (chunk_type == kGlbJsonChunk || chunk_type == kGlbBinChunk) {
            problem = "GLB chunk " + std::to_string(chunk) + " repeats the " +
                      chunk_type_name(chunk_type) + " chunk";
            return {};
        }
        // Chunks of other types are skipped, as the specification requires.
        offset = data_begin + chunk_length;
    }
    if (layout.json.empty()) {
        problem = "truncated GLB: no JSON chunk";
        return {};
    }
    return layout;
}

std::vector<std::uint8_t> build_glb(const std::string& json, std::span<const std::uint8_t> bin) {
    const auto padded = [](std::size_t n) { return (n + 3) / 4 * 4; };
    const std::size_t json_chunk = padded(json.size());
    const std::size_t bin_chunk = padded(bin.size());
    const std::size_t total = 12 + 8 + json_chunk + (bin.empty() ? 0 : 8 + bin_chunk);

    std::vector<std::uint8_t> out;
    out.reserve(total);
    append_u32(out, kGlbMagic);
    append_u32(out, 2);
    append_u32(out, static_cast<std::uint32_t>(total));
    append_u32(out, static_cast<std::uint32_t>(json_chunk));
    append_u32(out, kGlbJsonChunk);
    out.insert(out.end(), json.begin(), json.end());
    out.resize(out.size() + json_chunk - json.size(), ' ');  // the spec pads JSON with spaces
    if (!bin.empty()) {
        append_u32(out, static_cast<std::uint32_t>(bin_chunk));
        append_u32(out, kGlbBinChunk);
        out.insert(out.end(), bin.begin(), bin.end());
        out.resize(out.size() + bin_chunk - bin.size(), 0);
    }
    return out;
}

std::string base64_encode(std::span<const std::uint8_t> bytes) {
    static constexpr char kAlphabet[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    std::size_t i = 0;
    for (; i + 3 <= bytes.size(); i += 3) {
        const std::uint32_t group = (static_cast<std::uint32_t>(bytes[i]) << 16) |
                                    (static_cast<std::uint32_t>(bytes[i + 1]) << 8) |
                                    static_cast<std::uint32_t>(bytes[i + 2]);
        out += kAlphabet[(group >> 18) & 63];
        out += kAlphabet[(group >> 12) & 63];
        out += kAlphabet[(group >> 6) & 63];
        out += kAlphabet[group & 63];
    }
    const std::size_t rest = bytes.size() - i;
    if (rest > 0) {
        std::uint32_t group = static_cast<std::uint32_t>(bytes[i]) << 16;
        if (rest == 2) {
            group |= static_cast<std::uint32_t>(bytes[i + 1]) << 8;
        }
        out += kAlphabet[(group >> 18) & 63];
        out += kAlphabet[(group >> 12) & 63];
        out += rest == 2 ? kAlphabet[(group >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

}  // namespace luxel::scene::gltf_detail
