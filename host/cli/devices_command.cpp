#include <cstdio>

#include "cl/device.hpp"
#include "cli/commands.hpp"

namespace clpath {

Command add_devices_command(CLI::App& app) {
    app.add_subcommand("devices", "List OpenCL devices with the index and name --device accepts");
    return [] {
        const auto devices = list_devices();
        if (devices.empty()) {
            std::printf("No OpenCL device found (is an ICD installed? On Debian: apt install pocl-opencl-icd).\n");
            return 1;
        }
        std::string platform;
        for (const auto& d : devices) {
            if (d.platform_name != platform) {
                platform = d.platform_name;
                std::printf("%s\n", platform.c_str());
            }
            std::printf("  %s\n", d.describe().c_str());
        }
        std::printf("Default: first GPU, else first CPU; --device INDEX|NAME or CLPATH_DEVICE choose another.\n");
        return 0;
    };
}

}  // namespace clpath
