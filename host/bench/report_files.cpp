#include "bench/report_files.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "util/error.hpp"

namespace clpath {
namespace fs = std::filesystem;

void check_report_path(const std::string& path, const std::string& what) {
    if (path.empty()) throw Error(what + ": empty file name");
    fs::path dir = fs::path(path).parent_path();
    if (dir.empty()) dir = ".";
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) throw Error(what + " " + path + ": folder " + dir.string() + " does not exist");
    if (::access(dir.c_str(), W_OK) != 0)
        throw Error(what + " " + path + ": folder " + dir.string() + " is not writable");
    if (fs::is_directory(path, ec)) throw Error(what + " " + path + ": is a folder");
}

void write_report_file(const std::string& path, const std::string& text) {
    const fs::path p(path);
    const fs::path tmp = p.parent_path() / (std::string(".") + p.filename().string() + ".tmp" + std::to_string(::getpid()));
    {
        std::ofstream out(tmp, std::ios::binary);
        if (!out) throw Error("cannot write " + tmp.string() + ": " + std::strerror(errno));
        out << text;
        out.close();
        if (!out) {
            std::error_code ec;
            fs::remove(tmp, ec);
            throw Error("cannot write " + path + ": " + std::strerror(errno));
        }
    }
    std::error_code ec;
    fs::rename(tmp, p, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw Error("cannot write " + path + ": " + ec.message());
    }
}

std::string csv_field(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

}  // namespace clpath
