#pragma once
// What the driver says about a compiled kernel on a device
// (clGetKernelWorkGroupInfo): its private memory per work-item (registers
// spilled or arrays), and the work-group size multiple it prefers (a warp,
// a wavefront, or PoCL's vector width).
#include <cstddef>
#include <string>

#include "cl/context.hpp"

namespace clpath {

struct KernelInfo {
    std::string name;
    unsigned long long private_mem_bytes = 0;  // CL_KERNEL_PRIVATE_MEM_SIZE
    unsigned long long local_mem_bytes = 0;    // CL_KERNEL_LOCAL_MEM_SIZE
    std::size_t preferred_multiple = 0;        // CL_KERNEL_PREFERRED_WORK_GROUP_SIZE_MULTIPLE
    std::size_t max_work_group = 0;            // CL_KERNEL_WORK_GROUP_SIZE
};

// Throws clpath::Error when the driver refuses a query.
KernelInfo kernel_info(const Kernel& kernel, cl_device_id device);

// "batch_trace_closest: private 1024 B, local 0 B, preferred multiple 8, at most 4096 per group"
std::string describe(const KernelInfo& info);

}  // namespace clpath
