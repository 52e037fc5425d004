#pragma once

#include <string>

#include <glm/glm.hpp>

#include "luxel/runtime/gl_objects.hpp"

namespace luxel::gl {

/// A linked GLSL program. Built by ShaderLibrary; uniforms are set with DSA calls, so the
/// program need not be bound. Setting a uniform the linker removed is a no-op (as in GL).
class Program : public Handle<ProgramDeleter> {
  public:
    Program() = default;
    explicit Program(GLuint id, std::string label) : Handle(id), label_(std::move(label)) {}

    void use() const;
    [[nodiscard]] GLint uniform_location(const char* name) const;
    void set(const char* name, int value) const;
    void set(const char* name, float value) const;
    void set(const char* name, const glm::vec2& value) const;
    void set(const char* name, const glm::vec3& value) const;
    void set(const char* name, const glm::vec4& value) const;
    void set(const char* name, const glm::mat3& value) const;
    void set(const char* name, const glm::mat4& value) const;

    /// The shader files it was built from, for messages.
    [[nodiscard]] const std::string& label() const { return label_; }

  private:
    std::string label_;
};

}  // namespace luxel::gl
