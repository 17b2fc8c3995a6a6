#include "viewer/window.hpp"

#include <algorithm>
#include <cctype>

#include "util/error.hpp"
#include "viewer/gl.hpp"
#include "viewer/keymap.hpp"

namespace clpath::viewer {
namespace {

// GLFW reports errors through a callback; keep the last one for the message.
std::string g_glfw_error;
void on_glfw_error(int, const char* description) { g_glfw_error = description ? description : "unknown"; }

}  // namespace

std::string key_name(int key) {
    switch (key) {
        case GLFW_KEY_ESCAPE: return "escape";
        case GLFW_KEY_TAB: return "tab";
        case GLFW_KEY_F12: return "f12";
        case GLFW_KEY_KP_ADD: return "=";
        case GLFW_KEY_KP_SUBTRACT: return "-";
        default: break;
    }
    // GLFW's printable keys are their ASCII codes (upper case letters).
    if (key >= 32 && key < 127) return std::string(1, char(std::tolower(key)));
    return "";
}

Window::Window(int width, int height, const std::string& title) {
    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit())
        throw Error("cannot open a window: " + g_glfw_error +
                    " (the viewer needs a display; without one, run it under xvfb-run)");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!window_) {
        const std::string why = g_glfw_error;
        glfwTerminate();
        throw Error("cannot create an OpenGL 3.3 window: " + why);
    }
    glfwMakeContextCurrent(window_);
    glfwSwapInterval(0);  // the frame budget paces the loop, not the display's refresh
    glfwSetWindowUserPointer(window_, this);
    glfwSetKeyCallback(window_, on_key);
    glfwSetScrollCallback(window_, on_scroll);
    glfwGetCursorPos(window_, &last_cursor_.x, &last_cursor_.y);
}

Window::~Window() {
    if (window_) glfwDestroyWindow(window_);
    glfwTerminate();
}

void Window::on_key(GLFWwindow* w, int key, int, int action, int) {
    auto* self = static_cast<Window*>(glfwGetWindowUserPointer(w));
    if (action != GLFW_PRESS) return;
    const std::string name = key_name(key);
    if (!name.empty() && !is_movement_key(name)) self->pending_.pressed.push_back(name);
}

void Window::on_scroll(GLFWwindow* w, double, double dy) {
    auto* self = static_cast<Window*>(glfwGetWindowUserPointer(w));
    if (!self->mouse_captured_) self->pending_.scroll += float(dy);
}

WindowInput Window::poll(bool mouse_captured) {
    mouse_captured_ = mouse_captured;
    glfwPollEvents();
    WindowInput in = std::move(pending_);
    pending_ = {};
    for (const char* k : {"w", "a", "s", "d", "q", "e"})
        if (glfwGetKey(window_, std::toupper(k[0])) == GLFW_PRESS) in.held.push_back(k);
    glm::dvec2 cursor;
    glfwGetCursorPos(window_, &cursor.x, &cursor.y);
    const bool down = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    // A drag starts only outside the heads-up display, and follows the cursor from there.
    if (down && (dragging_ || !mouse_captured)) {
        if (dragging_) {
            in.drag = glm::vec2(cursor - last_cursor_);
        } else {
            press_at_ = cursor;
            press_travel_ = 0;
        }
        press_travel_ = std::max(press_travel_, glm::length(cursor - press_at_));
        dragging_ = true;
    } else {
        // A press that ends where it began is a click, not a look around.
        if (dragging_ && !down && press_travel_ <= kClickSlop) in.click = glm::vec2(cursor);
        dragging_ = false;
    }
    last_cursor_ = cursor;
    return in;
}

bool Window::should_close() const { return glfwWindowShouldClose(window_); }

glm::ivec2 Window::framebuffer_size() const {
    glm::ivec2 s;
    glfwGetFramebufferSize(window_, &s.x, &s.y);
    return s;
}

glm::vec2 Window::framebuffer_per_window_pixel() const {
    int w = 0, h = 0;
    glfwGetWindowSize(window_, &w, &h);
    const glm::ivec2 fb = framebuffer_size();
    return {w > 0 ? float(fb.x) / float(w) : 1.0f, h > 0 ? float(fb.y) / float(h) : 1.0f};
}

void Window::resize(int width, int height) { glfwSetWindowSize(window_, width, height); }

void Window::swap() { glfwSwapBuffers(window_); }

}  // namespace clpath::viewer
