#pragma once
// Choosing several OpenCL devices at once: --device all, --device 0,1,
// --device gpu,cpu. Each comma-separated item is what select_device() takes.
#include <string>
#include <vector>

#include "cl/device.hpp"

namespace clpath {

// "all": every device of every platform. Otherwise each item is resolved by
// select_device(); a device named twice is an error (two contexts on one
// device would only compete for it). An empty spec is one default device.
std::vector<DeviceInfo> select_devices(const std::string& spec);

}  // namespace clpath
