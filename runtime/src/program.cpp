#include "luxel/runtime/program.hpp"

#include <glm/gtc/type_ptr.hpp>

namespace luxel::gl {

void Program::use() const {
    glUseProgram(id());
}

GLint Program::uniform_location(const char* name) const {
    return glGetUniformLocation(id(), name);
}

void Program::set(const char* name, int value) const {
    glProgramUniform1i(id(), uniform_location(name), value);
}
void Program::set(const char* name, float value) const {
    glProgramUniform1f(id(), uniform_location(name), value);
}
void Program::set(const char* name, const glm::vec2& value) const {
    glProgramUniform2fv(id(), uniform_location(name), 1, glm::value_ptr(value));
}
void Program::set(const char* name, const glm::vec3& value) const {
    glProgramUniform3fv(id(), uniform_location(name), 1, glm::value_ptr(value));
}
void Program::set(const char* name, const glm::vec4& value) const {
    glProgramUniform4fv(id(), uniform_location(name), 1, glm::value_ptr(value));
}
void Program::set(const char* name, const glm::mat3& value) const {
    glProgramUniformMatrix3fv(id(), uniform_location(name), 1, GL_FALSE, glm::value_ptr(value));
}
void Program::set(const char* name, const glm::mat4& value) const {
    glProgramUniformMatrix4fv(id(), uniform_location(name), 1, GL_FALSE, glm::value_ptr(value));
}

}  // namespace luxel::gl
