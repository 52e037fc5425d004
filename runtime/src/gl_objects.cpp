#include "luxel/runtime/gl_objects.hpp"

#include <cstdio>
#include <limits>
#include <string>

#include "luxel/runtime/error.hpp"
#include "luxel/runtime/texture_sampling.hpp"

namespace luxel::gl {

void BufferDeleter::operator()(GLuint id) const {
    glDeleteBuffers(1, &id);
}
void TextureDeleter::operator()(GLuint id) const {
    glDeleteTextures(1, &id);
}
void FramebufferDeleter::operator()(GLuint id) const {
    glDeleteFramebuffers(1, &id);
}
void RenderbufferDeleter::operator()(GLuint id) const {
    glDeleteRenderbuffers(1, &id);
}
void VertexArrayDeleter::operator()(GLuint id) const {
    glDeleteVertexArrays(1, &id);
}
void QueryDeleter::operator()(GLuint id) const {
    glDeleteQueries(1, &id);
}
void ProgramDeleter::operator()(GLuint id) const {
    glDeleteProgram(id);
}
void ShaderDeleter::operator()(GLuint id) const {
    glDeleteShader(id);
}

namespace {

GLsizeiptr checked_size(std::size_t bytes, const char* what) {
    if (bytes > static_cast<std::size_t>(std::numeric_limits<GLsizeiptr>::max())) {
        throw Error(std::string(what) + ": size does not fit GLsizeiptr");
    }
    return static_cast<GLsizeiptr>(bytes);
}

void check_size(int width, int height, const char* what) {
    if (width <= 0 || height <= 0) {
        throw Error(std::string(what) + ": size must be positive, got " + std::to_string(width) +
                    "x" + std::to_string(height));
    }
}

}  // namespace

Buffer Buffer::create(std::size_t bytes, const void* data, GLbitfield flags) {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    Buffer buffer(id, bytes == 0 ? 1 : bytes);
    glNamedBufferStorage(id, checked_size(buffer.size_, "Buffer::create"), data, flags);
    check_error("Buffer::create");
    return buffer;
}

void Buffer::update(std::size_t offset, std::size_t bytes, const void* data) {
    if (offset > size_ || bytes > size_ - offset) {
        throw Error("Buffer::update: range [" + std::to_string(offset) + ", " +
                    std::to_string(offset + bytes) + ") exceeds buffer size " +
                    std::to_string(size_));
    }
    glNamedBufferSubData(id(), static_cast<GLintptr>(offset), checked_size(bytes, "Buffer::update"),
                         data);
}

Texture Texture::create(GLenum target) {
    GLuint id = 0;
    glCreateTextures(target, 1, &id);
    return Texture(id, target, 0, 0);
}

Texture Texture::create_2d(GLenum internal_format, int width, int height, int levels) {
    check_size(width, height, "Texture::create_2d");
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &id);
    Texture texture(id, GL_TEXTURE_2D, width, height);
    glTextureStorage2D(id, levels < 1 ? 1 : levels, internal_format, width, height);
    set_sampling(id, Sampling::Filtered);
    if (levels > 1) {
        glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    }
    check_error("Texture::create_2d");
    return texture;
}

Renderbuffer Renderbuffer::create(GLenum internal_format, int width, int height) {
    check_size(width, height, "Renderbuffer::create");
    GLuint id = 0;
    glCreateRenderbuffers(1, &id);
    Renderbuffer renderbuffer(id);
    glNamedRenderbufferStorage(id, internal_format, width, height);
    check_error("Renderbuffer::create");
    return renderbuffer;
}

Framebuffer Framebuffer::create() {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    return Framebuffer(id);
}

void Framebuffer::attach(GLenum attachment, const Texture& texture, int level) {
    glNamedFramebufferTexture(id(), attachment, texture.id(), level);
}

void Framebuffer::attach(GLenum attachment, const Renderbuffer& renderbuffer) {
    glNamedFramebufferRenderbuffer(id(), attachment, GL_RENDERBUFFER, renderbuffer.id());
}

void Framebuffer::check_complete(const char* what) const {
    const GLenum status = glCheckNamedFramebufferStatus(id(), GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        throw Error(std::string(what) + ": framebuffer incomplete (status 0x" + [&] {
            char hex[16];
            std::snprintf(hex, sizeof hex, "%04X", status);
            return std::string(hex);
        }() + ")");
    }
}

VertexArray VertexArray::create() {
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    return VertexArray(id);
}

Query Query::create(GLenum target) {
    GLuint id = 0;
    glCreateQueries(target, 1, &id);
    return Query(id, target);
}

}  // namespace luxel::gl
