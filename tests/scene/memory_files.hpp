#pragma once
// Scene and mesh files held in memory, so that each test states its input
// in full next to what it expects.
#include <filesystem>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "scene/load/load_options.hpp"
#include "util/error.hpp"

namespace clpath::test {

struct MemoryFiles {
    std::map<std::string, std::string> files;
    LoadOptions options() const {
        LoadOptions o;
        o.read_file = [this](const std::string& path) {
            auto it = files.find(std::filesystem::path(path).lexically_normal().string());
            if (it == files.end()) throw Error(path + ": no such file");
            return it->second;
        };
        o.file_exists = [this](const std::string& path) {
            return files.count(std::filesystem::path(path).lexically_normal().string()) > 0;
        };
        return o;
    }
};

// The message of the clpath::Error that f throws; fails the test if none.
template <class F>
std::string error_of(F&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    ADD_FAILURE() << "expected a clpath::Error";
    return "";
}

// Where the repository's bundled scenes are.
inline std::string scenes_dir() {
    return (std::filesystem::path(__FILE__).parent_path() / ".." / ".." / "scenes").lexically_normal().string();
}

}  // namespace clpath::test
