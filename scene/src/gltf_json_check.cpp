// The JSON pre-check that runs before tinygltf sees a byte: one streaming pass (nlohmann's SAX
// parser, no document built) that bounds the nesting, counts the top-level arrays against the
// limits before anything is allocated for them, and checks that every property the glTF schema
// types as an index or a count is a whole number >= 0. tinygltf drops a "mesh": 0.5 or an index
// beyond 64 bits without a word, so a node would silently lose its mesh.

#include <cstdint>
#include <limits>
#include <string_view>

#include "gltf_internal.hpp"

namespace luxel::scene::gltf_detail {
namespace {

/// Where the parser is: one entry per enclosing object member or array element.
struct Frame {
    bool array = false;
    std::uint64_t elements = 0;  ///< array: elements started so far
    std::string key;             ///< object: the member being read
};

/// Properties that hold an index (into another top-level array) or a count, as paths from the
/// root; "[]" stands for any array element, "*" for any member. Those under "extras" are free.
constexpr std::string_view kWholeNumberPaths[] = {
    "scene",
    "scenes/[]/nodes/[]",
    "nodes/[]/mesh",
    "nodes/[]/camera",
    "nodes/[]/skin",
    "nodes/[]/children/[]",
    "nodes/[]/extensions/KHR_lights_punctual/light",
    "meshes/[]/primitives/[]/indices",
    "meshes/[]/primitives/[]/material",
    "meshes/[]/primitives/[]/mode",
    "meshes/[]/primitives/[]/attributes/*",
    "meshes/[]/primitives/[]/targets/[]/*",
    "accessors/[]/bufferView",
    "accessors/[]/byteOffset",
    "accessors/[]/componentType",
    "accessors/[]/count",
    "accessors/[]/sparse/count",
    "accessors/[]/sparse/indices/bufferView",
    "accessors/[]/sparse/indices/byteOffset",
    "accessors/[]/sparse/indices/componentType",
    "accessors/[]/sparse/values/bufferView",
    "accessors/[]/sparse/values/byteOffset",
    "bufferViews/[]/buffer",
    "bufferViews/[]/byteOffset",
    "bufferViews/[]/byteLength",
    "bufferViews/[]/byteStride",
    "buffers/[]/byteLength",
    "images/[]/bufferView",
    "textures/[]/sampler",
    "textures/[]/source",
    "animations/[]/channels/[]/sampler",
    "animations/[]/channels/[]/target/node",
    "animations/[]/samplers/[]/input",
    "animations/[]/samplers/[]/output",
    "skins/[]/inverseBindMatrices",
    "skins/[]/skeleton",
    "skins/[]/joints/[]",
};

bool matches(std::string_view pattern, const std::vector<std::string_view>& path) {
    std::size_t at = 0;
    for (const std::string_view segment : path) {
        if (at > pattern.size()) {
            return false;
        }
        const std::size_t slash = std::min(pattern.find('/', at), pattern.size());
        const std::string_view wanted = pattern.substr(at, slash - at);
        if (wanted != "*" && wanted != segment) {
            return false;
        }
        at = slash + 1;
    }
    return at == pattern.size() + 1;
}

class JsonCheck {
  public:
    using json = nlohmann::json;
    explicit JsonCheck(const LoadOptions& limits) : limits_(limits) {}

    bool null() { return scalar("null"); }
    bool boolean(bool value) { return scalar(value ? "true" : "false"); }
    bool number_integer(json::number_integer_t value) {
        return value >= 0 ? element() : scalar(std::to_string(value));
    }
    bool number_unsigned(json::number_unsigned_t value) {
        // tinygltf keeps indices in an int: 2^32 would wrap to 0 and name the first mesh. Counts
        // and byte sizes are 64-bit there, and the importer bounds them itself.
        if (value >
                static_cast<json::number_unsigned_t>(std::numeric_limits<std::int32_t>::max()) &&
            wants_whole_number() && !holds_a_size()) {
            return scalar(std::to_string(value) + " (beyond 2^31 - 1)");
        }
        return element();
    }
    bool number_float(json::number_float_t /*value*/, const json::string_t& text) {
        return scalar(text);
    }
    bool string(json::string_t& value) { return scalar("\"" + value.substr(0, 40) + "\""); }
    bool binary(json::binary_t& /*value*/) { return scalar("binary data"); }
    bool key(json::string_t& value) {
        frames_.back().key = value;
        return true;
    }
    bool start_object(std::size_t /*elements*/) { return enter(false); }
    bool end_object() { return leave(); }
    bool start_array(std::size_t /*elements*/) { return enter(true); }
    bool end_array() { return leave(); }
    bool parse_error(std::size_t /*position*/, const std::string& /*last_token*/,
                     const nlohmann::detail::exception& error) {
        std::string message = error.what();
        // Drop nlohmann's "[json.exception.parse_error.101] " tag; keep line and column.
        if (const auto tag_end = message.find("] "); tag_end != std::string::npos) {
            message.erase(0, tag_end + 2);
        }
        problem_ = "invalid JSON: " + message;
        return false;
    }

    [[nodiscard]] const std::string& problem() const { return problem_; }

  private:
    /// The path of the value about to be read, array elements as "[]".
    [[nodiscard]] std::vector<std::string_view> path() const {
        std::vector<std::string_view> segments;
        segments.reserve(frames_.size());
        for (const Frame& frame : frames_) {
            segments.emplace_back(frame.array ? std::string_view("[]")
                                              : std::string_view(frame.key));
        }
        return segments;
    }

    /// "nodes[3].mesh", for messages.
    [[nodiscard]] std::string where() const {
        std::string text;
        for (const Frame& frame : frames_) {
            if (frame.array) {
                text += "[" + std::to_string(frame.elements - 1) + "]";
            } else {
                text += (text.empty() ? "" : ".") + frame.key;
            }
        }
        return text;
    }

    [[nodiscard]] bool wants_whole_number() const {
        if (frames_.empty()) {
            return false;
        }
        const std::vector<std::string_view> segments = path();
        for (const std::string_view segment : segments) {
            if (segment == "extras") {
                return false;
            }
        }
        for (const std::string_view pattern : kWholeNumberPaths) {
            if (matches(pattern, segments)) {
                return true;
            }
        }
        // A texture reference anywhere in a material: {"index": N} under "...Texture".
        const std::size_t n = segments.size();
        return n >= 3 && segments[0] == "materials" && segments[n - 1] == "index" &&
               segments[n - 2].ends_with("Texture");
    }

    /// Whether the value about to be read is a count or a byte size rather than an index.
    [[nodiscard]] bool holds_a_size() const {
        const std::string& key = frames_.back().key;
        return !frames_.back().array && (key == "count" || key == "byteOffset" ||
                                         key == "byteLength" || key == "byteStride");
    }

    /// Counts an array element where the value starts; fails past the limits before the
    /// element is read, so nothing is spent on a file that is too large.
    bool element() {
        if (frames_.empty() || !frames_.back().array) {
            return true;
        }
        const std::uint64_t count = ++frames_.back().elements;
        if (frames_.size() == 2 && !frames_[0].array) {
            const std::string& array = frames_[0].key;
            const std::uint64_t limit =
                array == "nodes" ? limits_.max_nodes : limits_.max_array_elements;
            if (count > limit) {
                problem_ = "more than the limit of " + std::to_string(limit) + " " + array +
                           " (--limit " +
                           (array == "nodes" ? std::string("nodes") : std::string("elements")) +
                           "=N raises it)";
                return false;
            }
        }
        if (frames_.size() == 4 && frames_[0].key == "extensions" &&
            frames_[1].key == "KHR_lights_punctual" && frames_[2].key == "lights" &&
            count > limits_.max_lights) {
            problem_ = "more than the limit of " + std::to_string(limits_.max_lights) +
                       " lights (KHR_lights_punctual; --limit lights=N raises it)";
            return false;
        }
        return true;
    }

    bool scalar(const std::string& text) {
        if (!element()) {
            return false;
        }
        if (wants_whole_number()) {
            problem_ = "invalid glTF: " + where() + " must be a whole number >= 0, got " + text;
            return false;
        }
        return true;
    }

    bool enter(bool array) {
        if (!frames_.empty() && !frames_.back().array && wants_whole_number()) {
            problem_ = "invalid glTF: " + where() + " must be a whole number >= 0, got " +
                       (array ? "an array" : "an object");
            return false;
        }
        if (!element()) {
            return false;
        }
        if (frames_.size() + 1 > limits_.max_json_depth) {
            problem_ = "invalid glTF: JSON nested deeper than " +
                       std::to_string(limits_.max_json_depth) + " levels";
            return false;
        }
        frames_.push_back(Frame{array, 0, {}});
        return true;
    }
    bool leave() {
        frames_.pop_back();
        return true;
    }

    const LoadOptions& limits_;
    std::vector<Frame> frames_;
    std::string problem_;
};

}  // namespace

std::string check_json(std::span<const std::uint8_t> text, const LoadOptions& limits) {
    JsonCheck check(limits);
    const auto* first = reinterpret_cast<const char*>(text.data());
    const bool ok = nlohmann::json::sax_parse(first, first + text.size(), &check);
    if (ok) {
        return {};
    }
    return check.problem().empty() ? std::string("invalid JSON") : check.problem();
}

}  // namespace luxel::scene::gltf_detail
