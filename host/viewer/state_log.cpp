#include "viewer/state_log.hpp"

#include "util/error.hpp"

namespace clpath::viewer {

StateLog::StateLog(const std::string& path) {
    if (path.empty()) return;
    out_.open(path, std::ios::trunc);
    if (!out_) throw Error("cannot write the state log " + path);
}

void StateLog::write(const nlohmann::json& record) {
    if (!out_.is_open()) return;
    out_ << record.dump() << '\n';
    out_.flush();  // a test reads it even if the viewer is killed
}

}  // namespace clpath::viewer
