#pragma once

#include <filesystem>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "luxel/runtime/error.hpp"
#include "luxel/runtime/program.hpp"

namespace luxel {

enum class ShaderStage { Vertex, TessControl, TessEvaluation, Geometry, Fragment, Compute };

/// A shader failed to load, compile or link. what() names the file (and line, for compile
/// errors), e.g. "shaders/foo.frag:12:3: error: syntax error ...".
class ShaderError : public Error {
  public:
    using Error::Error;
};

/// GLSL after #include expansion. The shader compiler numbers source strings; `files[n]` is the
/// file that `#line L n` directives in `text` refer to, so driver messages map back to files.
struct PreprocessedShader {
    std::string text;
    std::vector<std::filesystem::path> files;
};

/// Loads GLSL from disk at run time. Files are looked up in the search paths in order; the
/// default list is: $LUXEL_SHADER_DIR (override), the source tree's shaders/ (build-tree
/// binaries), and <exe>/../share/luxel/shaders (installed tree).
///
/// `#include "name"` is resolved relative to the including file, then the search paths; each
/// file is included once per shader (like #pragma once), and cycles are an error.
class ShaderLibrary {
  public:
    explicit ShaderLibrary(
        std::vector<std::filesystem::path> search_paths = default_search_paths());

    [[nodiscard]] static std::vector<std::filesystem::path> default_search_paths();
    [[nodiscard]] const std::vector<std::filesystem::path>& search_paths() const { return paths_; }

    /// Finds `name` in the search paths; throws ShaderError listing the paths tried.
    [[nodiscard]] std::filesystem::path resolve(const std::string& name) const;

    /// Reads `name`, expands includes, and inserts `defines` (lines such as "#define K 3")
    /// after the #version line.
    [[nodiscard]] PreprocessedShader preprocess(const std::string& name,
                                                const std::string& defines = {}) const;

    /// Compiles and links one program from (stage, file) pairs.
    [[nodiscard]] gl::Program build(
        std::initializer_list<std::pair<ShaderStage, std::string>> stages,
        const std::string& defines = {}) const;

  private:
    std::vector<std::filesystem::path> paths_;
};

/// Rewrites a driver's info log so "0:12(3): error" (Mesa) and "0(12) : error" (NVIDIA) name
/// the file: "<files[0]>:12:3: error". Exposed for tests.
[[nodiscard]] std::string map_shader_log(const std::string& log,
                                         const std::vector<std::filesystem::path>& files);

}  // namespace luxel
