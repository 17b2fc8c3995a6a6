#include "viewer/bvh_overlay.hpp"

#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "util/error.hpp"
#include "viewer/gl.hpp"

namespace clpath::viewer {
namespace {

const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 color;
uniform mat4 mvp;
out vec3 v_color;
void main() { gl_Position = mvp * vec4(position, 1.0); v_color = color; })";

const char* kFragmentShader = R"(#version 330 core
in vec3 v_color;
out vec4 frag;
void main() { frag = vec4(v_color, 1.0); })";

GLuint compile(GLenum type, const char* source) {
    GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &source, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        glGetShaderInfoLog(s, sizeof log, nullptr, log);
        glDeleteShader(s);
        throw Error(std::string("BVH overlay shader: ") + log);
    }
    return s;
}

// Shallow levels warm, deep ones cool, so nesting reads at a glance.
glm::vec3 level_color(int level) {
    const float h = std::fmod(0.13f * float(level - 1), 1.0f) * 6.0f;
    const float x = 1.0f - std::fabs(std::fmod(h, 2.0f) - 1.0f);
    const glm::vec3 rgb[6] = {{1, x, 0}, {x, 1, 0}, {0, 1, x}, {0, x, 1}, {x, 0, 1}, {1, 0, x}};
    return 0.35f + 0.65f * rgb[int(h) % 6];
}

}  // namespace

glm::mat4 view_projection(const Camera& c, glm::vec2 near_far) {
    const float aspect = float(c.width) / float(c.height);
    return glm::perspective(glm::radians(c.vfov_degrees), aspect, near_far.x, near_far.y) *
           glm::lookAt(c.eye, c.target, c.up);
}

BvhOverlay::BvhOverlay() {
    const GLuint vs = compile(GL_VERTEX_SHADER, kVertexShader);
    const GLuint fs = compile(GL_FRAGMENT_SHADER, kFragmentShader);
    program_ = glCreateProgram();
    glAttachShader(program_, vs);
    glAttachShader(program_, fs);
    glLinkProgram(program_);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(program_, GL_LINK_STATUS, &ok);
    if (!ok) throw Error("BVH overlay shader: link failed");
    mvp_location_ = glGetUniformLocation(program_, "mvp");
    glGenVertexArrays(1, &vao_);
    glGenBuffers(1, &vbo_);
    glBindVertexArray(vao_);
    glBindBuffer(GL_ARRAY_BUFFER, vbo_);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), reinterpret_cast<void*>(3 * sizeof(float)));
    glEnableVertexAttribArray(0);
    glEnableVertexAttribArray(1);
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
}

BvhOverlay::~BvhOverlay() {
    glDeleteBuffers(1, &vbo_);
    glDeleteVertexArrays(1, &vao_);
    glDeleteProgram(program_);
}

void BvhOverlay::set_boxes(const std::vector<LevelBox>& boxes) {
    std::vector<float> data;
    data.reserve(boxes.size() * 24 * 6);
    for (const LevelBox& b : boxes) {
        const glm::vec3 col = level_color(b.level);
        for (const glm::vec3& p : box_edges(b)) data.insert(data.end(), {p.x, p.y, p.z, col.x, col.y, col.z});
    }
    glBindBuffer(GL_ARRAY_BUFFER, vbo_);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(data.size() * sizeof(float)), data.data(), GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    vertex_count_ = int(data.size() / 6);
}

void BvhOverlay::draw(const Camera& camera, glm::ivec4 viewport, glm::vec2 near_far) const {
    if (vertex_count_ == 0 || viewport.z == 0) return;
    const glm::mat4 mvp = view_projection(camera, near_far);
    glViewport(viewport.x, viewport.y, viewport.z, viewport.w);
    glDisable(GL_DEPTH_TEST);  // every box shows, as in the thesis renderer's view
    glUseProgram(program_);
    glUniformMatrix4fv(mvp_location_, 1, GL_FALSE, glm::value_ptr(mvp));
    glBindVertexArray(vao_);
    glDrawArrays(GL_LINES, 0, vertex_count_);
    glBindVertexArray(0);
    glUseProgram(0);
}

}  // namespace clpath::viewer
