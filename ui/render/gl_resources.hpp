// Owning handles for OpenGL objects (move-only, deleted with their owner) and shader programs
// compiled from source with the driver's log in the error. Needs a current context.
#pragma once

#include <epoxy/gl.h>
#include <glm/mat4x4.hpp>

#include <string>
#include <utility>

namespace faultline::ui::gl {

// One GL name and the function that deletes it.
template <void (*Delete)(GLuint)> class Handle {
  public:
    Handle() = default;
    explicit Handle(GLuint id) : m_id(id) {}
    Handle(Handle&& o) noexcept : m_id(std::exchange(o.m_id, 0)) {}
    Handle& operator=(Handle&& o) noexcept {
        if (this != &o) {
            reset();
            m_id = std::exchange(o.m_id, 0);
        }
        return *this;
    }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
    ~Handle() { reset(); }
    GLuint id() const { return m_id; }
    explicit operator bool() const { return m_id != 0; }
    void reset() {
        if (m_id)
            Delete(m_id);
        m_id = 0;
    }

  private:
    GLuint m_id = 0;
};

void deleteBuffer(GLuint id);
void deleteTexture(GLuint id);
void deleteFramebuffer(GLuint id);
void deleteVertexArray(GLuint id);
void deleteProgram(GLuint id);

using Buffer = Handle<deleteBuffer>;
using Texture = Handle<deleteTexture>;
using Framebuffer = Handle<deleteFramebuffer>;
using VertexArray = Handle<deleteVertexArray>;
using Program = Handle<deleteProgram>;

Buffer makeBuffer();
Texture makeTexture();
Framebuffer makeFramebuffer();
VertexArray makeVertexArray();

// Sets a mat4 uniform of `program` (which must be in use), in single precision.
void setMat4(GLuint program, const char* name, const glm::dmat4& m);

// Compiles and links; throws std::runtime_error with `name`, the stage and the driver's log.
Program makeProgram(const std::string& name, const std::string& vertexSource,
                    const std::string& fragmentSource);

// A buffer exposed to shaders as a buffer texture (samplerBuffer / usamplerBuffer), for vertex
// pulling.
class BufferTexture {
  public:
    void upload(const void* data, std::size_t bytes, GLenum internalFormat);
    void bind(GLuint unit) const;
    bool empty() const { return !m_texture; }
    std::size_t size() const { return m_size; } // bytes of the last upload

  private:
    Buffer m_buffer;
    Texture m_texture;
    std::size_t m_size = 0;
};

// A framebuffer with an RGBA8 colour texture and optionally a 32-bit float depth texture.
class RenderTexture {
  public:
    void ensure(int width, int height, bool withDepth);
    // Colour of its own, depth borrowed from another target of the same size (depth-tested
    // layers drawn without touching that depth).
    void ensureSharingDepth(int width, int height, GLuint depthTexture);
    GLuint framebuffer() const { return m_fbo.id(); }
    GLuint color() const { return m_color.id(); }
    GLuint depth() const { return m_depth.id(); }
    int width() const { return m_width; }
    int height() const { return m_height; }

  private:
    Framebuffer m_fbo;
    Texture m_color;
    Texture m_depth;
    int m_width = 0, m_height = 0;
    bool m_withDepth = false;
    GLuint m_sharedDepth = 0;
};

// Strict GL checks (on in tests: FAULTLINE_GL_CHECKS=1, set by scripts/test.sh, or
// setStrictChecks): a uniform the program does not have, or a GL error after a render pass,
// throws std::logic_error naming it, instead of drawing nothing.
bool strictChecks();
void setStrictChecks(bool on);

// Uniform location by name; under strict checks a name the program lacks throws.
GLint uniformLocation(GLuint program, const char* name);
// For setters shared by programs that each use only some of the names (sampler units): -1 when
// the program lacks it, never a throw.
inline GLint optionalUniformLocation(GLuint program, const char* name) {
    return glGetUniformLocation(program, name);
}
inline GLint uniform(const Program& p, const char* name) { return uniformLocation(p.id(), name); }

// Under strict checks, throws when glGetError reports anything (named with `pass`).
void checkErrors(const char* pass);

} // namespace faultline::ui::gl
