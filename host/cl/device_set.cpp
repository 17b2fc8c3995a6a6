#include "cl/device_set.hpp"

#include <algorithm>
#include <sstream>

#include "util/error.hpp"

namespace clpath {

std::vector<DeviceInfo> select_devices(const std::string& spec) {
    if (spec == "all") {
        std::vector<DeviceInfo> all = list_devices();
        if (all.empty()) throw Error("--device all: no OpenCL device found");
        return all;
    }
    if (spec.find(',') == std::string::npos) return {select_device(spec)};
    if (spec.front() == ',' || spec.back() == ',')
        throw Error("--device '" + spec + "': an empty item in the device list");
    std::vector<DeviceInfo> out;
    std::stringstream ss(spec);
    std::string item;
    while (std::getline(ss, item, ',')) {
        if (item.empty()) throw Error("--device '" + spec + "': an empty item in the device list");
        if (item == "all") throw Error("--device '" + spec + "': 'all' cannot be combined with other devices");
        DeviceInfo d = select_device(item);
        const bool twice = std::any_of(out.begin(), out.end(), [&](const DeviceInfo& o) { return o.index == d.index; });
        if (twice)
            throw Error("--device '" + spec + "': device [" + std::to_string(d.index) + "] " + d.name +
                        " is named twice ('" + item + "')");
        out.push_back(std::move(d));
    }
    return out;
}

}  // namespace clpath
