#include "viewer/hud.hpp"

#include <cmath>

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include "util/error.hpp"
#include "viewer/gl.hpp"
#include "viewer/keymap.hpp"

namespace clpath::viewer {

Hud::Hud(GLFWwindow* window) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the user's folder
    ImGui::StyleColorsDark();
    if (!ImGui_ImplGlfw_InitForOpenGL(window, true) || !ImGui_ImplOpenGL3_Init("#version 330 core")) {
        ImGui::DestroyContext();
        throw Error("cannot start the heads-up display (Dear ImGui)");
    }
}

Hud::~Hud() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
}

bool Hud::wants_mouse() const { return visible_ && ImGui::GetIO().WantCaptureMouse; }

void Hud::draw(const HudState& s) {
    if (!visible_) return;
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    ImGui::SetNextWindowPos(ImVec2(8, 8));
    ImGui::SetNextWindowBgAlpha(0.65f);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                   ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoMove;
    if (ImGui::Begin("clpath", nullptr, flags)) {
        ImGui::Text("clpath  %s", s.scene.c_str());
        ImGui::Separator();
        if (s.denoise_problem) {  // at the top: the answer to a key just pressed
            ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.75f, 0.3f, 1.0f));
            ImGui::PushTextWrapPos(ImGui::GetFontSize() * 30);
            ImGui::TextUnformatted(s.denoise.c_str());
            ImGui::PopTextWrapPos();
            ImGui::PopStyleColor();
            ImGui::Separator();
        }
        if (ImGui::BeginTable("stats", 2)) {
            auto row = [](const char* label, const char* fmt, auto... args) {
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                ImGui::TextUnformatted(label);
                ImGui::TableNextColumn();
                ImGui::Text(fmt, args...);
            };
            if (s.max_spp)
                row("spp", "%llu / %llu", (unsigned long long)s.spp, (unsigned long long)s.max_spp);
            else
                row("spp", "%llu", (unsigned long long)s.spp);
            row("denoise", "%s", s.denoise_problem ? "see above" : s.denoise.c_str());
            row("frame", "%.1f ms (%.1f fps)", s.ms_per_frame, s.ms_per_frame > 0 ? 1000.0 / s.ms_per_frame : 0.0);
            row("samples", "%.2f M/s", s.msamples_per_s);
            row("rays", "%.2f M/s", s.mrays_per_s);
            row("device", "%s", s.device.c_str());
            row("triangles", "%zu", s.triangles);
            row("integrator", "%s", s.integrator.c_str());
            row("exposure", "%.2f (%+.1f EV)", s.exposure, std::log2(s.exposure));
            row("resolution", "%d x %d", s.width, s.height);
            row("display", "%s", s.display_path.c_str());
            if (s.bvh_depth)
                row("BVH boxes", "depth %d of %d", s.bvh_depth, s.bvh_levels);
            else
                row("BVH boxes", "off");
            if (s.aperture_radius > 0)
                row("lens", "aperture %.3g, focus %.4g (click)", s.aperture_radius, s.focus_distance);
            else
                row("lens", "pinhole");
            row("speed", "%.3g units/s", s.speed);
            ImGui::EndTable();
        }
        if (!s.error.empty()) {
            ImGui::Separator();
            ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.4f, 0.35f, 1.0f));
            ImGui::PushTextWrapPos(ImGui::GetFontSize() * 30);
            ImGui::TextUnformatted(s.error.c_str());
            ImGui::PopTextWrapPos();
            ImGui::PopStyleColor();
        }
        if (ImGui::CollapsingHeader("keys")) {
            for (const auto& [keys, what] : key_help()) ImGui::BulletText("%s: %s", keys.c_str(), what.c_str());
        }
    }
    ImGui::End();
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

}  // namespace clpath::viewer
