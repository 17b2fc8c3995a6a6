#pragma once
// Intel Open Image Denoise 2, loaded at run time (dlopen) so that clpath
// builds and runs without it; only --denoise and the viewer's denoise key
// need it. The functions are the few of its C API that clpath calls,
// declared here from the API documentation (OIDN 2.x, doc/api.md of
// https://github.com/RenderKit/oidn: "Devices", "Error Handling", "Images",
// "Filters", "RT"), so no OIDN header is needed at build time either.
#include <cstddef>
#include <string>
#include <vector>

namespace clpath {

// The values the documentation gives these enumerations (OIDNDeviceType,
// OIDNFormat, OIDNError).
constexpr int kOidnDeviceTypeCpu = 1;
constexpr int kOidnFormatFloat3 = 3;
constexpr int kOidnErrorNone = 0;

struct OidnApi {
    using Device = void*;  // OIDNDevice
    using Filter = void*;  // OIDNFilter
    Device (*new_device)(int type);
    void (*commit_device)(Device);
    void (*release_device)(Device);
    int (*get_device_error)(Device, const char** message);
    Filter (*new_filter)(Device, const char* type);
    void (*set_shared_filter_image)(Filter, const char* name, void* ptr, int format, std::size_t width,
                                    std::size_t height, std::size_t byte_offset, std::size_t pixel_stride,
                                    std::size_t row_stride);
    void (*set_filter_bool)(Filter, const char* name, bool value);
    void (*commit_filter)(Filter);
    void (*execute_filter)(Filter);
    void (*release_filter)(Filter);
    std::string path;  // the library file it came from
};

// Where the library is looked for, in order: $CLPATH_OIDN_LIBRARY alone when
// it is set (a file), else the virtual environment tools/install-deps.sh
// creates (the pyoidn wheel's copy), else the system loader's search for
// libOpenImageDenoise.so.2.
std::vector<std::string> oidn_library_candidates();

// Loads the library once per process and returns its functions. Throws
// clpath::Error saying what was tried and how to install it when none loads.
const OidnApi& oidn_api();

}  // namespace clpath
