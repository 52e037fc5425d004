#include "luxel/runtime/program_variants.hpp"

#include <utility>

#include "luxel/runtime/error.hpp"

namespace luxel {

ProgramVariants::ProgramVariants(const ShaderLibrary& shaders, std::string vertex,
                                 std::string fragment, std::vector<std::string> features,
                                 std::string defines)
    : shaders_(shaders),
      vertex_(std::move(vertex)),
      fragment_(std::move(fragment)),
      features_(std::move(features)),
      defines_(std::move(defines)) {
    if (features_.size() > 32) {
        throw Error("ProgramVariants: at most 32 features per program (" + fragment_ + ")");
    }
}

std::string ProgramVariants::defines_for(std::uint32_t mask) const {
    std::string lines = defines_;
    for (std::size_t bit = 0; bit < features_.size(); ++bit) {
        const bool on = ((mask >> bit) & 1u) != 0;
        lines += "#define " + features_[bit] + (on ? " 1\n" : " 0\n");
    }
    return lines;
}

const gl::Program& ProgramVariants::get(std::uint32_t mask) {
    // Bits past the features name nothing: one program for each distinct set.
    const std::uint32_t used =
        features_.size() >= 32 ? mask : mask & ((1u << features_.size()) - 1u);
    const auto found = programs_.find(used);
    if (found != programs_.end()) {
        return found->second;
    }
    gl::Program program = shaders_.build(
        {{ShaderStage::Vertex, vertex_}, {ShaderStage::Fragment, fragment_}}, defines_for(used));
    return programs_.emplace(used, std::move(program)).first->second;
}

}  // namespace luxel
