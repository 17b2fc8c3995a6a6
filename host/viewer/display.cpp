#include "viewer/display.hpp"

// gl.hpp first: GL/glx.h pulls in GL/gl.h, which must see GL_GLEXT_PROTOTYPES.
#include "viewer/gl.hpp"

#include <GL/glx.h>

#include <cstdio>

#include "util/error.hpp"
#include "viewer/letterbox.hpp"

namespace clpath::viewer {

DisplayContext make_display_context(const DeviceInfo& device) {
    DisplayContext d;
    if (!has_gl_sharing(device)) {
        d.context = std::make_unique<Context>(device);
        d.path = "read-back (" + device.name + " has no cl_khr_gl_sharing)";
        return d;
    }
    const auto props = glx_sharing_properties(device, glXGetCurrentContext(), glXGetCurrentDisplay());
    if (!device_drives_gl(device, props)) {
        d.context = std::make_unique<Context>(device);
        d.path = "read-back (the OpenGL context does not run on " + device.name + ")";
        return d;
    }
    try {
        d.context = std::make_unique<Context>(device, props);
        d.shared = true;
        d.path = "CL/GL sharing (cl_khr_gl_sharing)";
    } catch (const Error& e) {
        d.context = std::make_unique<Context>(device);
        d.path = std::string("read-back (a shared context failed: ") + e.what() + ")";
    }
    return d;
}

Display::Display(Context& ctx, bool shared) : ctx_(ctx), want_shared_(shared) {
    glGenTextures(1, &texture_);
    glGenFramebuffers(1, &framebuffer_);
    if (want_shared_) glGenBuffers(1, &pixel_buffer_);
}

Display::~Display() {
    shared_buffer_.reset();  // CL lets go of the GL buffer before GL deletes it
    if (pixel_buffer_) glDeleteBuffers(1, &pixel_buffer_);
    glDeleteFramebuffers(1, &framebuffer_);
    glDeleteTextures(1, &texture_);
}

void Display::resize(glm::ivec2 size) {
    size_ = size;
    glBindTexture(GL_TEXTURE_2D, texture_);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, size.x, size.y, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glBindTexture(GL_TEXTURE_2D, 0);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
    glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture_, 0);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    const std::size_t bytes = std::size_t(size.x) * size.y * 4;
    if (want_shared_) {
        shared_buffer_.reset();
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, pixel_buffer_);
        glBufferData(GL_PIXEL_UNPACK_BUFFER, GLsizeiptr(bytes), nullptr, GL_STREAM_DRAW);
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
        glFinish();
        try {
            shared_buffer_ = std::make_unique<GlSharedBuffer>(ctx_, pixel_buffer_, bytes);
        } catch (const Error& e) {
            // Sharing was promised but does not work: the read-back always does.
            std::fprintf(stderr, "clpath: display path: read-back (sharing the GL buffer failed: %s)\n", e.what());
            want_shared_ = false;
        }
    }
    if (!shared_buffer_) host_.resize(bytes);
}

void Display::upload(Renderer& renderer, float exposure) {
    const Camera& cam = renderer.camera();
    if (glm::ivec2(cam.width, cam.height) != size_) resize({cam.width, cam.height});
    renderer.resolve_on_device(exposure);
    glBindTexture(GL_TEXTURE_2D, texture_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    if (shared_buffer_) {
        glFinish();  // GL must be done with the buffer before CL takes it
        shared_buffer_->copy_from(renderer.srgb_buffer());
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, pixel_buffer_);
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, size_.x, size_.y, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    } else {
        ctx_.read(renderer.srgb_buffer(), host_.data(), host_.size());
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, size_.x, size_.y, GL_RGBA, GL_UNSIGNED_BYTE, host_.data());
    }
    glBindTexture(GL_TEXTURE_2D, 0);
}

void Display::upload(const std::vector<std::uint8_t>& rgba, glm::ivec2 size) {
    if (rgba.size() != std::size_t(size.x) * size.y * 4) throw Error("internal: display pixels of the wrong size");
    if (size != size_) resize(size);
    glBindTexture(GL_TEXTURE_2D, texture_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, size_.x, size_.y, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    glBindTexture(GL_TEXTURE_2D, 0);
}

glm::ivec4 Display::draw(glm::ivec2 fb) const {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glViewport(0, 0, fb.x, fb.y);
    glClearColor(0.08f, 0.08f, 0.08f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    const glm::ivec4 r = letterbox(size_, fb);
    if (r.z == 0) return r;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
    // Destination rows run top to bottom: texture row 0 is the image's top row.
    glBlitFramebuffer(0, 0, size_.x, size_.y, r.x, r.y + r.w, r.x + r.z, r.y, GL_COLOR_BUFFER_BIT,
                      r.z == size_.x && r.w == size_.y ? GL_NEAREST : GL_LINEAR);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    return r;
}

}  // namespace clpath::viewer
