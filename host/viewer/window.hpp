#pragma once
// The GLFW window and its OpenGL 3.3 context, and the input it collects
// between frames. Throws clpath::Error when there is no display.
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

struct GLFWwindow;

namespace clpath::viewer {

// What happened since the last frame.
struct WindowInput {
    std::vector<std::string> pressed;  // key names as in keymap.hpp, in order
    std::vector<std::string> held;     // movement keys down now
    glm::vec2 drag{0};                 // cursor movement with the left button down
    float scroll = 0;
    // A left click (press and release with the cursor moved at most
    // kClickSlop window pixels): where it was released, window pixels, y down.
    std::optional<glm::vec2> click;
};

inline constexpr double kClickSlop = 3.0;

class Window {
public:
    Window(int width, int height, const std::string& title);
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    GLFWwindow* get() const { return window_; }
    bool should_close() const;
    // Polls events and returns the input gathered since the last call.
    // mouse_captured: the heads-up display is using the mouse, so drags and
    // scrolls are its, not the camera's.
    WindowInput poll(bool mouse_captured);
    glm::ivec2 framebuffer_size() const;
    glm::vec2 framebuffer_per_window_pixel() const;  // 1 but on high-density displays
    void resize(int width, int height);
    void swap();

private:
    static void on_key(GLFWwindow* w, int key, int scancode, int action, int mods);
    static void on_scroll(GLFWwindow* w, double dx, double dy);

    GLFWwindow* window_ = nullptr;
    WindowInput pending_;
    glm::dvec2 last_cursor_{0};
    bool dragging_ = false;
    glm::dvec2 press_at_{0};
    double press_travel_ = 0;  // the farthest the cursor got from press_at_ while held
    bool mouse_captured_ = false;
};

// A key's name as keymap.hpp spells it ("w", "1", "[", "tab", "f12"); empty
// for keys the viewer does not use.
std::string key_name(int glfw_key);

}  // namespace clpath::viewer
