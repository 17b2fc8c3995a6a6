#include "cl/device.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <sstream>

#include "cl/errors.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

std::string device_string(cl_device_id d, cl_device_info what) {
    std::size_t n = 0;
    cl_check(clGetDeviceInfo(d, what, 0, nullptr, &n), "clGetDeviceInfo");
    std::string s(n, '\0');
    cl_check(clGetDeviceInfo(d, what, n, s.data(), nullptr), "clGetDeviceInfo");
    while (!s.empty() && (s.back() == '\0' || s.back() == ' ')) s.pop_back();
    return s;
}

template <class T>
T device_value(cl_device_id d, cl_device_info what) {
    T v{};
    cl_check(clGetDeviceInfo(d, what, sizeof v, &v, nullptr), "clGetDeviceInfo");
    return v;
}

std::string platform_string(cl_platform_id p, cl_platform_info what) {
    std::size_t n = 0;
    cl_check(clGetPlatformInfo(p, what, 0, nullptr, &n), "clGetPlatformInfo");
    std::string s(n, '\0');
    cl_check(clGetPlatformInfo(p, what, n, s.data(), nullptr), "clGetPlatformInfo");
    while (!s.empty() && s.back() == '\0') s.pop_back();
    return s;
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
}

std::string list_for_message(const std::vector<DeviceInfo>& devices) {
    if (devices.empty()) return "  (none: no OpenCL platform is installed; on Debian: apt install pocl-opencl-icd)";
    std::string s;
    for (const auto& d : devices) s += "  " + d.describe() + "\n";
    if (!s.empty()) s.pop_back();
    return s;
}

}  // namespace

std::string DeviceInfo::type_name() const { return is_gpu ? "GPU" : is_cpu ? "CPU" : "other"; }

std::string DeviceInfo::describe() const {
    std::ostringstream os;
    os.precision(3);
    os << "[" << index << "] " << name << " (" << type_name() << ", " << platform_name << ", " << version << ", "
       << compute_units << " CUs, " << double(global_mem) / (1u << 30) << " GiB)";
    return os.str();
}

std::vector<DeviceInfo> list_devices() {
    cl_uint np = 0;
    cl_int err = clGetPlatformIDs(0, nullptr, &np);
    if (err == -1001 /* CL_PLATFORM_NOT_FOUND_KHR: the ICD loader found no driver */ || np == 0) return {};
    cl_check(err, "clGetPlatformIDs");
    std::vector<cl_platform_id> platforms(np);
    cl_check(clGetPlatformIDs(np, platforms.data(), nullptr), "clGetPlatformIDs");
    std::vector<DeviceInfo> out;
    for (cl_platform_id p : platforms) {
        cl_uint nd = 0;
        err = clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, 0, nullptr, &nd);
        if (err == CL_DEVICE_NOT_FOUND || nd == 0) continue;
        cl_check(err, "clGetDeviceIDs");
        std::vector<cl_device_id> ids(nd);
        cl_check(clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, nd, ids.data(), nullptr), "clGetDeviceIDs");
        for (cl_device_id id : ids) {
            DeviceInfo d;
            d.index = int(out.size());
            d.platform = p;
            d.device = id;
            d.name = device_string(id, CL_DEVICE_NAME);
            d.platform_name = platform_string(p, CL_PLATFORM_NAME);
            d.version = device_string(id, CL_DEVICE_VERSION);
            d.driver = device_string(id, CL_DRIVER_VERSION);
            auto type = device_value<cl_device_type>(id, CL_DEVICE_TYPE);
            d.is_gpu = type & CL_DEVICE_TYPE_GPU;
            d.is_cpu = type & CL_DEVICE_TYPE_CPU;
            d.global_mem = device_value<cl_ulong>(id, CL_DEVICE_GLOBAL_MEM_SIZE);
            d.max_alloc = device_value<cl_ulong>(id, CL_DEVICE_MAX_MEM_ALLOC_SIZE);
            d.compute_units = device_value<cl_uint>(id, CL_DEVICE_MAX_COMPUTE_UNITS);
            d.max_work_group = device_value<std::size_t>(id, CL_DEVICE_MAX_WORK_GROUP_SIZE);
            out.push_back(d);
        }
    }
    return out;
}

DeviceInfo select_device(const std::string& spec_in) {
    std::string spec = spec_in;
    std::string origin = "--device";
    if (spec.empty()) {
        if (const char* env = std::getenv("CLPATH_DEVICE"); env && *env) {
            spec = env;
            origin = "CLPATH_DEVICE";
        }
    }
    const auto devices = list_devices();
    if (devices.empty())
        throw Error("no OpenCL device found.\n" + list_for_message(devices));
    if (spec.empty()) {
        for (const auto& d : devices)
            if (d.is_gpu) return d;
        for (const auto& d : devices)
            if (d.is_cpu) return d;
        return devices.front();
    }
    // By type, as other OpenCL tools take it: the first device of that kind.
    if (const std::string type = lower(spec); type == "cpu" || type == "gpu") {
        for (const auto& d : devices)
            if (type == "gpu" ? d.is_gpu : d.is_cpu) return d;
        throw UsageError(origin + " " + spec + ": no " + (type == "gpu" ? "GPU" : "CPU") + " device. Devices:\n" +
                         list_for_message(devices));
    }
    if (std::all_of(spec.begin(), spec.end(), [](unsigned char c) { return std::isdigit(c); })) {
        std::size_t i = spec.size() > 6 ? devices.size() : std::stoul(spec);
        if (i < devices.size()) return devices[i];
        throw UsageError(origin + " " + spec + ": no device with that index (the indices are 0 to " +
                         std::to_string(devices.size() - 1) + "). Devices:\n" + list_for_message(devices));
    }
    const std::string want = lower(spec);
    for (const auto& d : devices)
        if (lower(d.name).find(want) != std::string::npos) return d;
    for (const auto& d : devices)
        if (lower(d.platform_name).find(want) != std::string::npos) return d;
    throw UsageError(origin + " '" + spec + "': no device name matches. Devices:\n" + list_for_message(devices));
}

}  // namespace clpath
