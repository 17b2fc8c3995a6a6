#include "viewer/view_script.hpp"

#include <fstream>
#include <map>
#include <sstream>

#include "util/error.hpp"
#include "viewer/keymap.hpp"

namespace clpath::viewer {
namespace {

struct Syntax {
    ScriptCommand::Kind kind;
    int numbers;     // numeric arguments
    bool text;       // a leading word argument (key or file)
    bool optional_text = false;
};

const std::map<std::string, Syntax>& syntax() {
    using K = ScriptCommand::Kind;
    static const std::map<std::string, Syntax> s = {
        {"wait", {K::Wait, 1, false}},       {"wait-spp", {K::WaitSpp, 1, false}},
        {"wait-denoised", {K::WaitDenoised, 0, false}},
        {"key", {K::Key, 0, true}},          {"hold", {K::Hold, 1, true}},
        {"drag", {K::Drag, 2, false}},       {"scroll", {K::Scroll, 1, false}},
        {"click", {K::Click, 2, false}},
        {"screenshot", {K::Screenshot, 0, true, true}}, {"capture", {K::Capture, 0, true}},
        {"resize", {K::Resize, 2, false}},   {"camera", {K::Camera, 0, false}},
        {"quit", {K::Quit, 0, false}},
    };
    return s;
}

bool known_key(const std::string& k) { return is_movement_key(k) || action_for_key(k).has_value(); }

}  // namespace

std::vector<ScriptCommand> parse_view_script(const std::string& text, const std::string& source) {
    std::vector<ScriptCommand> out;
    std::istringstream lines(text);
    std::string line;
    for (int n = 1; std::getline(lines, line); ++n) {
        if (auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
        std::istringstream words(line);
        std::string name;
        if (!(words >> name)) continue;
        const std::string where = source + ":" + std::to_string(n) + ": ";
        auto it = syntax().find(name);
        if (it == syntax().end()) throw Error(where + "unknown command '" + name + "'");
        const Syntax& s = it->second;
        ScriptCommand c{s.kind, "", 0, 0, n};
        if (s.text && !(words >> c.text) && !s.optional_text) throw Error(where + "'" + name + "' needs an argument");
        double* nums[2] = {&c.a, &c.b};
        for (int i = 0; i < s.numbers; ++i)
            if (!(words >> *nums[i])) throw Error(where + "'" + name + "' needs " + std::to_string(s.numbers) + " number(s)");
        std::string extra;
        if (words >> extra) throw Error(where + "unexpected '" + extra + "' after '" + name + "'");
        using K = ScriptCommand::Kind;
        if ((c.kind == K::Key || c.kind == K::Hold) && !known_key(c.text))
            throw Error(where + "unknown key '" + c.text + "'");
        if ((c.kind == K::Wait || c.kind == K::Hold || c.kind == K::WaitSpp) && c.a < 0)
            throw Error(where + "'" + name + "' needs a count of zero or more");
        if (c.kind == K::Resize && (c.a < 1 || c.b < 1)) throw Error(where + "window size must be positive");
        if (c.kind == K::Click && (c.a < 0 || c.b < 0)) throw Error(where + "a click needs a window pixel (x, y >= 0)");
        out.push_back(c);
    }
    return out;
}

std::vector<ScriptCommand> load_view_script(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw Error("cannot read script " + path);
    std::stringstream ss;
    ss << in.rdbuf();
    return parse_view_script(ss.str(), path);
}

ScriptRunner::Step ScriptRunner::next_frame(std::uint64_t spp, bool denoise_caught_up) {
    using K = ScriptCommand::Kind;
    Step step;
    if (hold_frames_ > 0) {
        step.held.push_back(hold_key_);
        --hold_frames_;
        return step;  // a hold blocks the script until the key is released
    }
    while (next_ < commands_.size()) {
        const ScriptCommand& c = commands_[next_];
        if (c.kind == K::Wait) {
            if (!waiting_) {
                waiting_ = true;
                wait_frames_ = long(c.a);
            }
            if (wait_frames_ > 0) {
                --wait_frames_;
                return step;
            }
            waiting_ = false;
        } else if (c.kind == K::WaitSpp) {
            if (spp < std::uint64_t(c.a)) return step;
        } else if (c.kind == K::WaitDenoised) {
            // denoise_caught_up is from before this frame's commands, one of
            // which (key n) may have changed what there is to wait for.
            if (!denoise_caught_up || !step.commands.empty()) return step;
        } else if (c.kind == K::Hold) {
            hold_key_ = c.text;
            hold_frames_ = long(c.a);
            ++next_;
            if (hold_frames_ > 0) {
                step.held.push_back(hold_key_);
                --hold_frames_;
            }
            return step;
        } else {
            step.commands.push_back(c);
            if (c.kind == K::Capture) {
                // A capture shows the frame being drawn: what follows it must
                // wait for the next frame, or a key after it would show in it.
                ++next_;
                return step;
            }
        }
        ++next_;
    }
    return step;
}

}  // namespace clpath::viewer
