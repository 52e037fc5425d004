#pragma once

#include <cstddef>
#include <utility>

#include "luxel/runtime/gl.hpp"

/// Move-only RAII owners of OpenGL objects, created with the GL 4.5 direct-state-access entry
/// points. An object must be destroyed while the context that created it is current; keep the
/// GlContext alive longer than everything made with it.
namespace luxel::gl {

/// Owns one GL object name; Deleter frees it. Moving transfers ownership; a moved-from or
/// default-constructed handle holds 0 and frees nothing.
template <class Deleter>
class Handle {
  public:
    Handle() = default;
    explicit Handle(GLuint id) : id_(id) {}
    ~Handle() { reset(); }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
    Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
    Handle& operator=(Handle&& other) noexcept {
        if (this != &other) {
            reset();
            id_ = std::exchange(other.id_, 0);
        }
        return *this;
    }

    [[nodiscard]] GLuint id() const { return id_; }
    explicit operator bool() const { return id_ != 0; }
    void reset() {
        if (id_ != 0) {
            Deleter{}(id_);
            id_ = 0;
        }
    }

  private:
    GLuint id_ = 0;
};

struct BufferDeleter {
    void operator()(GLuint id) const;
};
struct TextureDeleter {
    void operator()(GLuint id) const;
};
struct FramebufferDeleter {
    void operator()(GLuint id) const;
};
struct RenderbufferDeleter {
    void operator()(GLuint id) const;
};
struct VertexArrayDeleter {
    void operator()(GLuint id) const;
};
struct QueryDeleter {
    void operator()(GLuint id) const;
};
struct ProgramDeleter {
    void operator()(GLuint id) const;
};
struct ShaderDeleter {
    void operator()(GLuint id) const;
};

/// An immutable-storage buffer object.
class Buffer : public Handle<BufferDeleter> {
  public:
    Buffer() = default;
    /// Allocates `bytes` (at least 1) with glNamedBufferStorage; `data` may be null.
    static Buffer create(std::size_t bytes, const void* data = nullptr,
                         GLbitfield flags = GL_DYNAMIC_STORAGE_BIT);
    /// Replaces [offset, offset + bytes); needs GL_DYNAMIC_STORAGE_BIT. Throws on overrun.
    void update(std::size_t offset, std::size_t bytes, const void* data);
    [[nodiscard]] std::size_t size() const { return size_; }

  private:
    explicit Buffer(GLuint id, std::size_t size) : Handle(id), size_(size) {}
    std::size_t size_ = 0;
};

class Texture : public Handle<TextureDeleter> {
  public:
    Texture() = default;
    static Texture create(GLenum target);
    /// A 2D texture with immutable storage; levels >= 1.
    static Texture create_2d(GLenum internal_format, int width, int height, int levels = 1);
    [[nodiscard]] GLenum target() const { return target_; }
    [[nodiscard]] int width() const { return width_; }
    [[nodiscard]] int height() const { return height_; }

  private:
    Texture(GLuint id, GLenum target, int width, int height)
        : Handle(id), target_(target), width_(width), height_(height) {}
    GLenum target_ = 0;
    int width_ = 0;
    int height_ = 0;
};

class Renderbuffer : public Handle<RenderbufferDeleter> {
  public:
    Renderbuffer() = default;
    static Renderbuffer create(GLenum internal_format, int width, int height);

  private:
    using Handle::Handle;
};

class Framebuffer : public Handle<FramebufferDeleter> {
  public:
    Framebuffer() = default;
    static Framebuffer create();
    void attach(GLenum attachment, const Texture& texture, int level = 0);
    void attach(GLenum attachment, const Renderbuffer& renderbuffer);
    /// Throws luxel::Error naming `what` and the completeness status if incomplete.
    void check_complete(const char* what) const;

  private:
    using Handle::Handle;
};

class VertexArray : public Handle<VertexArrayDeleter> {
  public:
    VertexArray() = default;
    static VertexArray create();

  private:
    using Handle::Handle;
};

class Query : public Handle<QueryDeleter> {
  public:
    Query() = default;
    static Query create(GLenum target);
    [[nodiscard]] GLenum target() const { return target_; }

  private:
    Query(GLuint id, GLenum target) : Handle(id), target_(target) {}
    GLenum target_ = 0;
};

}  // namespace luxel::gl
