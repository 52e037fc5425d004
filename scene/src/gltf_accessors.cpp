// Reading glTF accessors with every bound checked before a byte is read or a vector sized:
// tinygltf records what the JSON says and leaves the arithmetic to its caller.

#include <algorithm>
#include <cmath>
#include <cstring>

#include <tiny_gltf.h>

#include "gltf_internal.hpp"

namespace luxel::scene::gltf_detail {
namespace {

/// a + b and a * b on 64-bit sizes, reporting overflow instead of wrapping.
bool add_overflows(std::uint64_t a, std::uint64_t b, std::uint64_t& out) {
    return __builtin_add_overflow(a, b, &out);
}
bool mul_overflows(std::uint64_t a, std::uint64_t b, std::uint64_t& out) {
    return __builtin_mul_overflow(a, b, &out);
}

const char* type_name(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR:
            return "SCALAR";
        case TINYGLTF_TYPE_VEC2:
            return "VEC2";
        case TINYGLTF_TYPE_VEC3:
            return "VEC3";
        case TINYGLTF_TYPE_VEC4:
            return "VEC4";
        case TINYGLTF_TYPE_MAT2:
            return "MAT2";
        case TINYGLTF_TYPE_MAT3:
            return "MAT3";
        case TINYGLTF_TYPE_MAT4:
            return "MAT4";
        default:
            return "unknown";
    }
}

int type_for_components(int components) {
    switch (components) {
        case 1:
            return TINYGLTF_TYPE_SCALAR;
        case 2:
            return TINYGLTF_TYPE_VEC2;
        case 3:
            return TINYGLTF_TYPE_VEC3;
        case 16:
            return TINYGLTF_TYPE_MAT4;
        default:
            return TINYGLTF_TYPE_VEC4;
    }
}

std::size_t component_size(int component_type) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return 2;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return 4;
        default:
            return 0;  // INT, DOUBLE and anything else: not a glTF 2.0 accessor type luxel reads
    }
}

std::string component_name(int component_type, bool normalized) {
    std::string name;
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
            name = "BYTE";
            break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            name = "UNSIGNED_BYTE";
            break;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
            name = "SHORT";
            break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            name = "UNSIGNED_SHORT";
            break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            name = "UNSIGNED_INT";
            break;
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            name = "FLOAT";
            break;
        default:
            name = "component type " + std::to_string(component_type);
            break;
    }
    return normalized ? "normalized " + name : name;
}

/// Where an accessor's elements lie, all bounds already checked.
struct Layout {
    const std::uint8_t* first = nullptr;
    std::size_t count = 0;
    std::size_t stride = 0;
    int component_type = 0;
    bool normalized = false;
};

template <typename T>
T load(const std::uint8_t* p) {
    T value;
    std::memcpy(&value, p, sizeof(T));  // accessors need not be aligned in a hostile file
    return value;
}

/// One component as float, with glTF's normalization rules (spec 3.11: signed values map to
/// [-1, 1] with the most negative clamped).
float component_as_float(const std::uint8_t* p, int component_type, bool normalized) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return load<float>(p);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
            const float v = load<std::uint8_t>(p);
            return normalized ? v / 255.0f : v;
        }
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            const float v = load<std::int8_t>(p);
            return normalized ? std::max(v / 127.0f, -1.0f) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            const float v = load<std::uint16_t>(p);
            return normalized ? v / 65535.0f : v;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            const float v = load<std::int16_t>(p);
            return normalized ? std::max(v / 32767.0f, -1.0f) : v;
        }
        default:
            return 0.0f;  // excluded by locate()
    }
}

Layout locate(const ImportContext& context, int index, int expected_type,
              bool (*allowed)(int component_type, bool normalized), const std::string& usage) {
    const tinygltf::Model& model = context.model();
    const std::string where = "accessor " + std::to_string(index) + " (" + usage + ")";
    if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size()) {
        context.fail(where + ": out of range (the file has " +
                     std::to_string(model.accessors.size()) + " accessors)");
    }
    const tinygltf::Accessor& accessor = model.accessors[static_cast<std::size_t>(index)];
    if (accessor.sparse.isSparse) {
        context.fail(where + ": sparse accessors are not supported");
    }
    if (accessor.type != expected_type) {
        context.fail(where + ": type " + type_name(accessor.type) + ", expected " +
                     type_name(expected_type));
    }
    if (!allowed(accessor.componentType, accessor.normalized)) {
        context.fail(where + ": " + component_name(accessor.componentType, accessor.normalized) +
                     " components are not allowed here");
    }
    const std::uint64_t count = accessor_count(context, index, usage);
    if (accessor.bufferView < 0 ||
        static_cast<std::size_t>(accessor.bufferView) >= model.bufferViews.size()) {
        context.fail(where + ": bufferView " + std::to_string(accessor.bufferView) +
                     " out of range (accessors without a bufferView are not supported)");
    }
    const tinygltf::BufferView& view =
        model.bufferViews[static_cast<std::size_t>(accessor.bufferView)];
    const std::string view_name = "bufferView " + std::to_string(accessor.bufferView);
    if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size()) {
        context.fail(where + ": " + view_name + " names buffer " + std::to_string(view.buffer) +
                     ", out of range");
    }
    const std::vector<unsigned char>& buffer =
        model.buffers[static_cast<std::size_t>(view.buffer)].data;
    std::uint64_t view_end = 0;
    if (add_overflows(view.byteOffset, view.byteLength, view_end) || view_end > buffer.size()) {
        context.fail(where + ": " + view_name + " (byteOffset " + std::to_string(view.byteOffset) +
                     ", byteLength " + std::to_string(view.byteLength) +
                     ") runs past the end of buffer " + std::to_string(view.buffer) + " (" +
                     std::to_string(buffer.size()) + " bytes)");
    }

    const std::size_t components = static_cast<std::size_t>(
        tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(expected_type)));
    const std::size_t size = component_size(accessor.componentType);
    const std::uint64_t element_size = components * size;
    std::uint64_t stride = element_size;
    if (view.byteStride != 0) {
        if (view.byteStride < element_size || view.byteStride > 252 ||
            view.byteStride % size != 0) {
            context.fail(where + ": " + view_name + " byteStride " +
                         std::to_string(view.byteStride) + " is invalid for " +
                         std::to_string(element_size) + "-byte elements");
        }
        stride = view.byteStride;
    }
    // The last element ends at byteOffset + (count - 1) * stride + element_size.
    std::uint64_t span = 0;
    std::uint64_t end = 0;
    if (mul_overflows(count - 1, stride, span) || add_overflows(span, element_size, span) ||
        add_overflows(span, accessor.byteOffset, end) || end > view.byteLength) {
        context.fail(where + ": " + std::to_string(count) + " elements of " +
                     std::to_string(element_size) + " bytes (stride " + std::to_string(stride) +
                     ") from byteOffset " + std::to_string(accessor.byteOffset) +
                     " run past the end of " + view_name + " (" + std::to_string(view.byteLength) +
                     " bytes)");
    }

    Layout layout;
    layout.first = buffer.data() + view.byteOffset + accessor.byteOffset;
    layout.count = static_cast<std::size_t>(count);
    layout.stride = static_cast<std::size_t>(stride);
    layout.component_type = accessor.componentType;
    layout.normalized = accessor.normalized;
    return layout;
}

bool float_only(int component_type, bool normalized) {
    return component_type == TINYGLTF_COMPONENT_TYPE_FLOAT && !normalized;
}

bool float_or_normalized(int component_type, bool normalized) {
    return float_only(component_type, normalized) ||
           (normalized && component_type != TINYGLTF_COMPONENT_TYPE_FLOAT &&
            component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT &&
            component_size(component_type) != 0);
}

bool index_type(int component_type, bool normalized) {
    return !normalized && (component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                           component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
                           component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
}

bool joint_type(int component_type, bool normalized) {
    return !normalized && (component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                           component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
}

}  // namespace

std::uint64_t accessor_count(const ImportContext& context, int index, const std::string& usage) {
    const tinygltf::Model& model = context.model();
    const std::string where = "accessor " + std::to_string(index) + " (" + usage + ")";
    if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size()) {
        context.fail(where + ": out of range (the file has " +
                     std::to_string(model.accessors.size()) + " accessors)");
    }
    const std::uint64_t count = model.accessors[static_cast<std::size_t>(index)].count;
    if (count == 0) {
        context.fail(where + ": count is 0");
    }
    if (count > context.options().max_accessor_elements) {
        context.fail(where + ": count " + std::to_string(count) + " exceeds the limit of " +
                     std::to_string(context.options().max_accessor_elements) + " elements");
    }
    return count;
}

std::vector<float> read_floats(const ImportContext& context, int index, int components,
                               bool allow_normalized, const std::string& usage) {
    const Layout layout = locate(context, index, type_for_components(components),
                                 allow_normalized ? float_or_normalized : float_only, usage);
    const auto per_element = static_cast<std::size_t>(components);
    const std::size_t size = component_size(layout.component_type);
    std::vector<float> values(layout.count * per_element);
    for (std::size_t e = 0; e < layout.count; ++e) {
        const std::uint8_t* element = layout.first + e * layout.stride;
        for (std::size_t c = 0; c < per_element; ++c) {
            const float value =
                component_as_float(element + c * size, layout.component_type, layout.normalized);
            if (!std::isfinite(value)) {
                context.fail("accessor " + std::to_string(index) + " (" + usage + "): element " +
                             std::to_string(e) + " is not finite (" + std::to_string(value) + ")");
            }
            values[e * per_element + c] = value;
        }
    }
    return values;
}

std::vector<std::uint32_t> read_indices(const ImportContext& context, int index,
                                        const std::string& usage) {
    const Layout layout = locate(context, index, TINYGLTF_TYPE_SCALAR, index_type, usage);
    std::vector<std::uint32_t> values(layout.count);
    for (std::size_t e = 0; e < layout.count; ++e) {
        const std::uint8_t* p = layout.first + e * layout.stride;
        switch (layout.component_type) {
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
                values[e] = load<std::uint8_t>(p);
                break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
                values[e] = load<std::uint16_t>(p);
                break;
            default:
                values[e] = load<std::uint32_t>(p);
                break;
        }
    }
    return values;
}

std::vector<glm::u16vec4> read_joints(const ImportContext& context, int index,
                                      const std::string& usage) {
    const Layout layout = locate(context, index, TINYGLTF_TYPE_VEC4, joint_type, usage);
    const std::size_t size = component_size(layout.component_type);
    std::vector<glm::u16vec4> values(layout.count);
    for (std::size_t e = 0; e < layout.count; ++e) {
        const std::uint8_t* element = layout.first + e * layout.stride;
        for (std::size_t c = 0; c < 4; ++c) {
            values[e][static_cast<glm::length_t>(c)] =
                size == 1 ? load<std::uint8_t>(element + c) : load<std::uint16_t>(element + 2 * c);
        }
    }
    return values;
}

}  // namespace luxel::scene::gltf_detail
