#include "luxel/runtime/shader_library.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>
#include <system_error>

#include "luxel/runtime/gl.hpp"

namespace luxel {
namespace fs = std::filesystem;

namespace {

// Includes nest this deep at most: far beyond any real shader, and a bound on runaway input.
constexpr int kMaxIncludeDepth = 32;

std::string read_text(const fs::path& path) {
    std::ifstream file(path, std::ios::binary);
    if (!file) {
        throw ShaderError(path.string() + ": cannot open shader file");
    }
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
}

std::vector<std::string> split_lines(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream stream(text);
    for (std::string line; std::getline(stream, line);) {
        if (!line.empty() && line.back() == '\r') {
            line.pop_back();
        }
        lines.push_back(std::move(line));
    }
    return lines;
}

fs::path canonical_or_self(const fs::path& path) {
    std::error_code ec;
    fs::path canonical = fs::weakly_canonical(path, ec);
    return ec ? path : canonical;
}

fs::path executable_directory() {
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    return ec ? fs::path() : exe.parent_path();
}

GLenum gl_stage(ShaderStage stage) {
    switch (stage) {
        case ShaderStage::Vertex:
            return GL_VERTEX_SHADER;
        case ShaderStage::TessControl:
            return GL_TESS_CONTROL_SHADER;
        case ShaderStage::TessEvaluation:
            return GL_TESS_EVALUATION_SHADER;
        case ShaderStage::Geometry:
            return GL_GEOMETRY_SHADER;
        case ShaderStage::Fragment:
            return GL_FRAGMENT_SHADER;
        case ShaderStage::Compute:
            return GL_COMPUTE_SHADER;
    }
    return GL_VERTEX_SHADER;
}

/// Expands #include directives depth-first, tracking which file each output line came from.
class IncludeExpander {
  public:
    IncludeExpander(const ShaderLibrary& library, std::string defines)
        : library_(library), defines_(std::move(defines)) {}

    PreprocessedShader run(const fs::path& top) {
        expand(top, 0);
        return std::move(output_);
    }

  private:
    void expand(const fs::path& file, int depth) {
        const fs::path canonical = canonical_or_self(file);
        const int index = static_cast<int>(output_.files.size());
        output_.files.push_back(file);
        included_.push_back(canonical);
        stack_.push_back(canonical);

        static const std::regex include_pattern(R"(^\s*#\s*include\s+(.*?)\s*$)");
        static const std::regex quoted_pattern(R"re(^"([^"]+)"$)re");
        static const std::regex version_pattern(R"(^\s*#\s*version\b.*$)");

        const auto lines = split_lines(read_text(file));
        if (depth > 0) {
            output_.text += line_directive(1, index);
        }
        for (std::size_t i = 0; i < lines.size(); ++i) {
            const std::string& line = lines[i];
            const std::size_t line_number = i + 1;
            const std::string where = file.string() + ":" + std::to_string(line_number);
            std::smatch match;
            if (std::regex_match(line, version_pattern)) {
                if (depth > 0) {
                    throw ShaderError(where + ": #version belongs only in the top-level shader");
                }
                output_.text += line + "\n";
                if (!defines_.empty()) {
                    output_.text += defines_;
                    if (defines_.back() != '\n') {
                        output_.text += "\n";
                    }
                }
                output_.text += line_directive(line_number + 1, index);
            } else if (std::regex_match(line, match, include_pattern)) {
                std::smatch quoted;
                const std::string argument = match[1].str();
                if (!std::regex_match(argument, quoted, quoted_pattern)) {
                    throw ShaderError(where + ": expected #include \"file\", got #include " +
                                      argument);
                }
                include(quoted[1].str(), file, where, depth);
                output_.text += line_directive(line_number + 1, index);
            } else {
                output_.text += line + "\n";
            }
        }
        stack_.pop_back();
    }

    void include(const std::string& name, const fs::path& from, const std::string& where,
                 int depth) {
        if (depth + 1 > kMaxIncludeDepth) {
            throw ShaderError(where + ": includes nest deeper than " +
                              std::to_string(kMaxIncludeDepth));
        }
        fs::path target = from.parent_path() / name;
        if (!fs::is_regular_file(target)) {
            try {
                target = library_.resolve(name);
            } catch (const ShaderError& e) {
                throw ShaderError(where + ": #include \"" + name + "\": " + e.what());
            }
        }
        const fs::path canonical = canonical_or_self(target);
        if (std::find(stack_.begin(), stack_.end(), canonical) != stack_.end()) {
            throw ShaderError(where + ": #include \"" + name + "\" forms a cycle");
        }
        if (std::find(included_.begin(), included_.end(), canonical) != included_.end()) {
            return;  // included once per shader, like #pragma once
        }
        expand(target, depth + 1);
    }

    static std::string line_directive(std::size_t line, int file_index) {
        return "#line " + std::to_string(line) + " " + std::to_string(file_index) + "\n";
    }

    const ShaderLibrary& library_;
    std::string defines_;
    PreprocessedShader output_;
    std::vector<fs::path> included_;
    std::vector<fs::path> stack_;
};

std::string info_log_of_shader(GLuint shader) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    glGetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), nullptr, log.data());
    log.resize(std::char_traits<char>::length(log.c_str()));
    return log;
}

std::string info_log_of_program(GLuint program) {
    GLint length = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    glGetProgramInfoLog(program, static_cast<GLsizei>(log.size()), nullptr, log.data());
    log.resize(std::char_traits<char>::length(log.c_str()));
    return log;
}

}  // namespace

ShaderLibrary::ShaderLibrary(std::vector<fs::path> search_paths)
    : paths_(std::move(search_paths)) {}

std::vector<fs::path> ShaderLibrary::default_search_paths() {
    std::vector<fs::path> paths;
    if (const char* env = std::getenv("LUXEL_SHADER_DIR"); env != nullptr && *env != '\0') {
        std::istringstream list(env);
        for (std::string entry; std::getline(list, entry, ':');) {
            if (!entry.empty()) {
                paths.emplace_back(entry);
            }
        }
    }
    paths.emplace_back(LUXEL_SHADER_SOURCE_DIR);
    if (const fs::path exe = executable_directory(); !exe.empty()) {
        paths.push_back(exe.parent_path() / LUXEL_SHADER_INSTALL_DIR);
    }
    return paths;
}

fs::path ShaderLibrary::resolve(const std::string& name) const {
    if (fs::path(name).is_absolute()) {
        if (fs::is_regular_file(name)) {
            return name;
        }
        throw ShaderError("shader file not found: " + name);
    }
    std::string tried;
    for (const auto& directory : paths_) {
        const fs::path candidate = directory / name;
        if (fs::is_regular_file(candidate)) {
            return candidate;
        }
        tried += (tried.empty() ? "" : ", ") + candidate.string();
    }
    throw ShaderError("shader file '" + name + "' not found; tried: " +
                      (tried.empty() ? std::string("(no search paths)") : tried));
}

PreprocessedShader ShaderLibrary::preprocess(const std::string& name,
                                             const std::string& defines) const {
    return IncludeExpander(*this, defines).run(resolve(name));
}

std::string map_shader_log(const std::string& log, const std::vector<fs::path>& files) {
    // Mesa: "0:12(3): error: ..."  NVIDIA: "0(12) : error C0000: ..."  AMD: "ERROR: 0:12: ..."
    static const std::regex mesa(R"(^(\d+):(\d+)\((\d+)\): (.*)$)");
    static const std::regex nvidia(R"(^(\d+)\((\d+)\) : (.*)$)");
    static const std::regex amd(R"(^(ERROR|WARNING): (\d+):(\d+): (.*)$)");
    auto file_name = [&](const std::string& index_text) {
        const std::size_t index = std::stoul(index_text);
        return index < files.size() ? files[index].string() : "<source " + index_text + ">";
    };
    std::string mapped;
    for (const auto& line : split_lines(log)) {
        std::smatch m;
        if (std::regex_match(line, m, mesa)) {
            mapped += file_name(m[1]) + ":" + m[2].str() + ":" + m[3].str() + ": " + m[4].str();
        } else if (std::regex_match(line, m, nvidia)) {
            mapped += file_name(m[1]) + ":" + m[2].str() + ": " + m[3].str();
        } else if (std::regex_match(line, m, amd)) {
            std::string kind = m[1].str();
            std::transform(kind.begin(), kind.end(), kind.begin(),
                           [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
            mapped += file_name(m[2]) + ":" + m[3].str() + ": " + kind + ": " + m[4].str();
        } else {
            mapped += line;
        }
        mapped += "\n";
    }
    return mapped;
}

gl::Program ShaderLibrary::build(std::initializer_list<std::pair<ShaderStage, std::string>> stages,
                                 const std::string& defines) const {
    std::string label;
    for (const auto& [stage, name] : stages) {
        label += (label.empty() ? "" : " + ") + name;
    }
    std::vector<gl::Handle<gl::ShaderDeleter>> shaders;
    for (const auto& [stage, name] : stages) {
        const PreprocessedShader source = preprocess(name, defines);
        gl::Handle<gl::ShaderDeleter> shader(glCreateShader(gl_stage(stage)));
        const char* text = source.text.c_str();
        glShaderSource(shader.id(), 1, &text, nullptr);
        glCompileShader(shader.id());
        GLint compiled = GL_FALSE;
        glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &compiled);
        if (compiled != GL_TRUE) {
            throw ShaderError("shader compilation failed:\n" +
                              map_shader_log(info_log_of_shader(shader.id()), source.files));
        }
        shaders.push_back(std::move(shader));
    }
    gl::Program program(glCreateProgram(), label);
    for (const auto& shader : shaders) {
        glAttachShader(program.id(), shader.id());
    }
    glLinkProgram(program.id());
    GLint linked = GL_FALSE;
    glGetProgramiv(program.id(), GL_LINK_STATUS, &linked);
    for (const auto& shader : shaders) {
        glDetachShader(program.id(), shader.id());
    }
    if (linked != GL_TRUE) {
        throw ShaderError("linking " + label + " failed:\n" + info_log_of_program(program.id()));
    }
    return program;
}

}  // namespace luxel
