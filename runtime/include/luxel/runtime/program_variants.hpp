#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "luxel/runtime/program.hpp"
#include "luxel/runtime/shader_library.hpp"

namespace luxel {

/// One program in the variants its features ask for: each feature is a
/// preprocessor switch of the fragment shader (`#define NAME 1` or `0`), so code a frame does not
/// need is compiled out rather than skipped by a branch. A software rasterizer such as llvmpipe
/// runs both sides of every branch for its whole block of pixels (the bicubic light-map path, the
/// probes and the sky cost every pixel of a level that has none of them: docs/PERFORMANCE.md,
/// "Shader variants"), and on a GPU the unused paths still take registers. A variant is built on
/// its first use and kept (a level uses a few); its shader files are looked up then.
class ProgramVariants {
  public:
    /// `features[i]` is the macro that bit i of a variant's mask switches; `defines` is put
    /// before them in every variant.
    ProgramVariants(const ShaderLibrary& shaders, std::string vertex, std::string fragment,
                    std::vector<std::string> features, std::string defines = {});

    /// The program with the features whose bits `mask` sets, built now if it is new (throws
    /// ShaderError as ShaderLibrary::build does).
    const gl::Program& get(std::uint32_t mask);

    /// The preprocessor lines that select `mask`'s variant, in the order of the features.
    [[nodiscard]] std::string defines_for(std::uint32_t mask) const;
    [[nodiscard]] std::size_t built() const { return programs_.size(); }

  private:
    ShaderLibrary shaders_;  ///< a copy: variants are built long after the caller's may be gone
    std::string vertex_;
    std::string fragment_;
    std::vector<std::string> features_;
    std::string defines_;
    std::map<std::uint32_t, gl::Program> programs_;
};

}  // namespace luxel
