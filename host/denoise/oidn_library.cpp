#include "denoise/oidn_library.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <mutex>

#include "util/error.hpp"

#ifndef CLPATH_OIDN_VENV
#define CLPATH_OIDN_VENV "/opt/clpath-oidn"
#endif

namespace clpath {
namespace {

namespace fs = std::filesystem;
constexpr const char* kSoname = "libOpenImageDenoise.so.2";

// The pyoidn wheel keeps the library (with its core, CPU device and TBB,
// found through its $ORIGIN run path) in pyoidn/oidn/lib of site-packages;
// the Python version in the path is the interpreter's.
std::vector<std::string> venv_libraries(const fs::path& venv) {
    std::vector<std::string> found;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(venv / "lib", ec)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind("python3", 0) != 0) continue;
        const fs::path lib = entry.path() / "site-packages/pyoidn/oidn/lib" / kSoname;
        if (fs::exists(lib, ec)) found.push_back(lib.string());
    }
    std::sort(found.begin(), found.end());
    return found;
}

template <typename F>
void bind(void* handle, const std::string& path, const char* symbol, F& out) {
    void* f = dlsym(handle, symbol);
    if (!f) throw Error(path + ": not Open Image Denoise 2: it has no " + symbol);
    out = reinterpret_cast<F>(f);
}

std::unique_ptr<OidnApi> load(const std::string& path, void* handle) {
    auto api = std::make_unique<OidnApi>();
    bind(handle, path, "oidnNewDevice", api->new_device);
    bind(handle, path, "oidnCommitDevice", api->commit_device);
    bind(handle, path, "oidnReleaseDevice", api->release_device);
    bind(handle, path, "oidnGetDeviceError", api->get_device_error);
    bind(handle, path, "oidnNewFilter", api->new_filter);
    bind(handle, path, "oidnSetSharedFilterImage", api->set_shared_filter_image);
    bind(handle, path, "oidnSetFilterBool", api->set_filter_bool);
    bind(handle, path, "oidnCommitFilter", api->commit_filter);
    bind(handle, path, "oidnExecuteFilter", api->execute_filter);
    bind(handle, path, "oidnReleaseFilter", api->release_filter);
    api->path = path;
    return api;
}

const char* const kHowToInstall =
    "install it with tools/install-deps.sh (the pyoidn wheel from PyPI, in a virtual environment at " CLPATH_OIDN_VENV
    "), or set CLPATH_OIDN_LIBRARY to the path of a libOpenImageDenoise.so.2";

}  // namespace

std::vector<std::string> oidn_library_candidates() {
    if (const char* env = std::getenv("CLPATH_OIDN_LIBRARY"); env && *env) return {env};
    std::vector<std::string> c = venv_libraries(CLPATH_OIDN_VENV);
    c.push_back(kSoname);  // no slash: the system loader's search path
    return c;
}

const OidnApi& oidn_api() {
    static std::mutex mutex;
    static std::unique_ptr<OidnApi> api;
    std::lock_guard<std::mutex> lock(mutex);
    if (api) return *api;
    const char* env = std::getenv("CLPATH_OIDN_LIBRARY");
    const bool from_env = env && *env;
    std::string tried;
    for (const std::string& path : oidn_library_candidates()) {
        // Kept loaded for the process's life: its thread pool outlives any one filter.
        if (void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL)) {
            api = load(path, handle);
            return *api;
        }
        const char* why = dlerror();
        tried += std::string("\n  ") + path + ": " + (why ? why : "not loaded");
    }
    if (from_env)
        throw Error(std::string("denoising needs Intel Open Image Denoise 2, and CLPATH_OIDN_LIBRARY=") + env +
                    " does not load it:" + tried + "\n" + kHowToInstall);
    throw Error(std::string("denoising needs Intel Open Image Denoise 2 (") + kSoname +
                "), which was not found (tried the virtual environment " CLPATH_OIDN_VENV
                " and the system loader):" + tried + "\n" + kHowToInstall);
}

}  // namespace clpath
