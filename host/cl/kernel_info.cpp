#include "cl/kernel_info.hpp"

#include <cstdio>

#include "cl/errors.hpp"

namespace clpath {

KernelInfo kernel_info(const Kernel& kernel, cl_device_id device) {
    KernelInfo info;
    info.name = kernel.name();
    auto query = [&](cl_kernel_work_group_info what, auto& value, const char* label) {
        cl_check(clGetKernelWorkGroupInfo(kernel.get(), device, what, sizeof value, &value, nullptr),
                 "clGetKernelWorkGroupInfo(" + kernel.name() + ", " + label + ")");
    };
    cl_ulong priv = 0, local = 0;
    std::size_t multiple = 0, max_group = 0;
    query(CL_KERNEL_PRIVATE_MEM_SIZE, priv, "CL_KERNEL_PRIVATE_MEM_SIZE");
    query(CL_KERNEL_LOCAL_MEM_SIZE, local, "CL_KERNEL_LOCAL_MEM_SIZE");
    query(CL_KERNEL_PREFERRED_WORK_GROUP_SIZE_MULTIPLE, multiple, "CL_KERNEL_PREFERRED_WORK_GROUP_SIZE_MULTIPLE");
    query(CL_KERNEL_WORK_GROUP_SIZE, max_group, "CL_KERNEL_WORK_GROUP_SIZE");
    info.private_mem_bytes = priv;
    info.local_mem_bytes = local;
    info.preferred_multiple = multiple;
    info.max_work_group = max_group;
    return info;
}

std::string describe(const KernelInfo& k) {
    char buf[256];
    std::snprintf(buf, sizeof buf, "%s: private %llu B, local %llu B, preferred multiple %zu, at most %zu per group",
                  k.name.c_str(), k.private_mem_bytes, k.local_mem_bytes, k.preferred_multiple, k.max_work_group);
    return buf;
}

}  // namespace clpath
