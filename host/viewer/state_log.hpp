#pragma once
// A JSON Lines record of the viewer's state, one line a frame plus one per
// event (screenshot, capture, camera): what tests check, and a trace for
// anyone debugging what the viewer did.
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

namespace clpath::viewer {

class StateLog {
public:
    StateLog() = default;
    explicit StateLog(const std::string& path);  // empty path: log nothing
    void write(const nlohmann::json& record);
    explicit operator bool() const { return out_.is_open(); }

private:
    std::ofstream out_;
};

}  // namespace clpath::viewer
