#pragma once
// Finding OpenCL devices and choosing one from a user's --device spec.
#include <CL/cl.h>

#include <string>
#include <vector>

namespace clpath {

struct DeviceInfo {
    int index = -1;  // position in list_devices(): what --device accepts
    cl_platform_id platform = nullptr;
    cl_device_id device = nullptr;
    std::string name, platform_name, version, driver;
    bool is_gpu = false, is_cpu = false;
    cl_ulong global_mem = 0, max_alloc = 0;
    cl_uint compute_units = 0;
    std::size_t max_work_group = 0;

    std::string type_name() const;
    std::string describe() const;  // "[0] NVIDIA H100 (GPU, NVIDIA CUDA, OpenCL 3.0 CUDA, 132 CUs, 79.1 GiB)"
};

// Every device of every platform, in a stable order. Empty when no OpenCL
// platform is installed (that is not an error here; choosing then is).
std::vector<DeviceInfo> list_devices();

// spec: "cpu" or "gpu" (the first device of that type), an index into
// list_devices(), or a case-insensitive substring of the device or platform
// name. Empty spec: $CLPATH_DEVICE if set, else the first
// GPU, else the first CPU device. Throws clpath::Error naming what was asked
// for and what exists (a UsageError when devices exist but none matches).
DeviceInfo select_device(const std::string& spec);

}  // namespace clpath
