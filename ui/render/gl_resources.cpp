#include "ui/render/gl_resources.hpp"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

namespace faultline::ui::gl {

void deleteBuffer(GLuint id) { glDeleteBuffers(1, &id); }
void deleteTexture(GLuint id) { glDeleteTextures(1, &id); }
void deleteFramebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
void deleteVertexArray(GLuint id) { glDeleteVertexArrays(1, &id); }
void deleteProgram(GLuint id) { glDeleteProgram(id); }

Buffer makeBuffer() {
    GLuint id = 0;
    glGenBuffers(1, &id);
    return Buffer(id);
}
Texture makeTexture() {
    GLuint id = 0;
    glGenTextures(1, &id);
    return Texture(id);
}
Framebuffer makeFramebuffer() {
    GLuint id = 0;
    glGenFramebuffers(1, &id);
    return Framebuffer(id);
}
VertexArray makeVertexArray() {
    GLuint id = 0;
    glGenVertexArrays(1, &id);
    return VertexArray(id);
}

namespace {

GLuint compile(const std::string& name, GLenum stage, const std::string& source) {
    const GLuint shader = glCreateShader(stage);
    const char* text = source.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
        std::vector<char> log(static_cast<std::size_t>(length) + 1, '\0');
        glGetShaderInfoLog(shader, length, nullptr, log.data());
        glDeleteShader(shader);
        throw std::runtime_error("shader '" + name + "' (" +
                                 (stage == GL_VERTEX_SHADER ? "vertex" : "fragment") +
                                 ") does not compile: " + log.data());
    }
    return shader;
}

} // namespace

void setMat4(GLuint program, const char* name, const glm::dmat4& m) {
    const glm::mat4 f(m);
    glUniformMatrix4fv(uniformLocation(program, name), 1, GL_FALSE, glm::value_ptr(f));
}

Program makeProgram(const std::string& name, const std::string& vertexSource,
                    const std::string& fragmentSource) {
    const GLuint vs = compile(name, GL_VERTEX_SHADER, vertexSource);
    GLuint fs = 0;
    try {
        fs = compile(name, GL_FRAGMENT_SHADER, fragmentSource);
    } catch (...) {
        glDeleteShader(vs);
        throw;
    }
    Program program(glCreateProgram());
    glAttachShader(program.id(), vs);
    glAttachShader(program.id(), fs);
    glLinkProgram(program.id());
    glDetachShader(program.id(), vs);
    glDetachShader(program.id(), fs);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetProgramiv(program.id(), GL_INFO_LOG_LENGTH, &length);
        std::vector<char> log(static_cast<std::size_t>(length) + 1, '\0');
        glGetProgramInfoLog(program.id(), length, nullptr, log.data());
        throw std::runtime_error("shader '" + name + "' does not link: " + log.data());
    }
    return program;
}

void BufferTexture::upload(const void* data, std::size_t bytes, GLenum internalFormat) {
    if (!m_buffer) {
        m_buffer = makeBuffer();
        m_texture = makeTexture();
    }
    // Fresh storage each time (the driver need not wait for draws still reading the old data);
    // a zero-sized buffer texture is not allowed, so keep at least 16 bytes.
    const std::size_t size = std::max<std::size_t>(bytes, 16);
    glBindBuffer(GL_TEXTURE_BUFFER, m_buffer.id());
    glBufferData(GL_TEXTURE_BUFFER, static_cast<GLsizeiptr>(size), nullptr, GL_DYNAMIC_DRAW);
    if (bytes)
        glBufferSubData(GL_TEXTURE_BUFFER, 0, static_cast<GLsizeiptr>(bytes), data);
    glBindBuffer(GL_TEXTURE_BUFFER, 0);
    glBindTexture(GL_TEXTURE_BUFFER, m_texture.id());
    glTexBuffer(GL_TEXTURE_BUFFER, internalFormat, m_buffer.id());
    glBindTexture(GL_TEXTURE_BUFFER, 0);
    m_size = bytes;
}

void BufferTexture::bind(GLuint unit) const {
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_BUFFER, m_texture.id());
}

void RenderTexture::ensureSharingDepth(int width, int height, GLuint depthTexture) {
    ensure(width, height, false);
    if (m_sharedDepth == depthTexture)
        return;
    glBindFramebuffer(GL_FRAMEBUFFER, m_fbo.id());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depthTexture, 0);
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("cannot share a depth texture (status " + std::to_string(status) +
                                 ")");
    m_sharedDepth = depthTexture;
}

void RenderTexture::ensure(int width, int height, bool withDepth) {
    if (m_fbo && width == m_width && height == m_height && withDepth == m_withDepth)
        return;
    if (m_fbo && withDepth == m_withDepth) {
        // A new size for the same textures: their names stay valid. The workbench's draw lists
        // are built before the views render, so a view whose cell changed size this frame
        // (a splitter dragged, a toolbar wrapped) would otherwise be drawn from a texture
        // deleted a moment before: GL_INVALID_OPERATION and a blank view for a frame.
        m_width = width;
        m_height = height;
        glBindTexture(GL_TEXTURE_2D, m_color.id());
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                     nullptr);
        if (withDepth) {
            glBindTexture(GL_TEXTURE_2D, m_depth.id());
            glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, width, height, 0,
                         GL_DEPTH_COMPONENT, GL_FLOAT, nullptr);
        }
        glBindTexture(GL_TEXTURE_2D, 0);
        glBindFramebuffer(GL_FRAMEBUFFER, m_fbo.id());
        const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        if (status == GL_FRAMEBUFFER_COMPLETE)
            return;
        // Not complete (a borrowed depth of another size): made anew below.
    }
    m_sharedDepth = 0;
    m_fbo = makeFramebuffer();
    m_color = makeTexture();
    m_depth.reset();
    m_width = width;
    m_height = height;
    m_withDepth = withDepth;
    glBindTexture(GL_TEXTURE_2D, m_color.id());
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindFramebuffer(GL_FRAMEBUFFER, m_fbo.id());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, m_color.id(), 0);
    if (withDepth) {
        m_depth = makeTexture();
        glBindTexture(GL_TEXTURE_2D, m_depth.id());
        glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, width, height, 0, GL_DEPTH_COMPONENT,
                     GL_FLOAT, nullptr);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, m_depth.id(), 0);
    }
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glBindTexture(GL_TEXTURE_2D, 0);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("cannot make a " + std::to_string(width) + "x" +
                                 std::to_string(height) + " render target (status " +
                                 std::to_string(status) + ")");
}

namespace {
std::atomic<int> g_strict{-1}; // -1: not decided yet (read the environment once)
} // namespace

bool strictChecks() {
    int v = g_strict.load();
    if (v < 0) {
        const char* env = std::getenv("FAULTLINE_GL_CHECKS");
        v = env && *env == '1' ? 1 : 0;
        g_strict.store(v);
    }
    return v == 1;
}

void setStrictChecks(bool on) { g_strict.store(on ? 1 : 0); }

GLint uniformLocation(GLuint program, const char* name) {
    const GLint at = glGetUniformLocation(program, name);
    if (at < 0 && strictChecks())
        throw std::logic_error(std::string("OpenGL: program ") + std::to_string(program) +
                               " has no active uniform \"" + name + "\"");
    return at;
}

void checkErrors(const char* pass) {
    if (!strictChecks())
        return;
    std::string errors;
    for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError()) {
        char code[16];
        std::snprintf(code, sizeof code, "0x%04x", e);
        errors += (errors.empty() ? "" : ", ") + std::string(code);
        if (errors.size() > 200)
            break;
    }
    if (!errors.empty())
        throw std::logic_error(std::string("OpenGL error after ") + pass + ": " + errors);
}

} // namespace faultline::ui::gl
