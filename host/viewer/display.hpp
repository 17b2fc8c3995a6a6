#pragma once
// How the renderer's image reaches the window. With cl_khr_gl_sharing the
// sRGB image is copied on the device into a GL pixel buffer; otherwise it is
// read back to the host and uploaded. Either way it lands in one texture,
// which is blitted (scaled, flipped: row 0 is the top) into the window.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cl/context.hpp"
#include "cl/gl_sharing.hpp"
#include "render/renderer.hpp"

namespace clpath::viewer {

// The OpenCL context for the viewer: shared with the current GL context when
// the device can, else a plain one. path says which and why.
struct DisplayContext {
    std::unique_ptr<Context> context;
    bool shared = false;
    std::string path;
};
DisplayContext make_display_context(const DeviceInfo& device);

class Display {
public:
    Display(Context& ctx, bool shared);
    ~Display();
    Display(const Display&) = delete;
    Display& operator=(const Display&) = delete;

    // Resolves the renderer's mean with exposure and brings it into the texture.
    void upload(Renderer& renderer, float exposure);
    // Brings host pixels (RGBA8 sRGB, row 0 at the top, of the renderer's size) into the texture instead.
    void upload(const std::vector<std::uint8_t>& rgba, glm::ivec2 size);
    // Clears the framebuffer and draws the image letterboxed; returns where it went.
    glm::ivec4 draw(glm::ivec2 framebuffer) const;
    glm::ivec2 image_size() const { return size_; }
    bool shared() const { return shared_buffer_ != nullptr; }

private:
    void resize(glm::ivec2 size);

    Context& ctx_;
    bool want_shared_;
    glm::ivec2 size_{0};
    unsigned texture_ = 0, framebuffer_ = 0, pixel_buffer_ = 0;
    std::unique_ptr<GlSharedBuffer> shared_buffer_;
    std::vector<std::uint8_t> host_;
};

}  // namespace clpath::viewer
