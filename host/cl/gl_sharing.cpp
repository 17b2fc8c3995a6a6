#include "cl/gl_sharing.hpp"

#include <CL/cl_gl.h>

#include <algorithm>

#include "util/error.hpp"

namespace clpath {

bool has_gl_sharing(const DeviceInfo& device) {
    std::size_t size = 0;
    if (clGetDeviceInfo(device.device, CL_DEVICE_EXTENSIONS, 0, nullptr, &size) != CL_SUCCESS) return false;
    std::string ext(size, '\0');
    if (clGetDeviceInfo(device.device, CL_DEVICE_EXTENSIONS, size, ext.data(), nullptr) != CL_SUCCESS) return false;
    return ext.find("cl_khr_gl_sharing") != std::string::npos;
}

std::vector<cl_context_properties> glx_sharing_properties(const DeviceInfo& device, void* glx_context,
                                                          void* x_display) {
    return {CL_CONTEXT_PLATFORM, cl_context_properties(device.platform),
            CL_GL_CONTEXT_KHR,   cl_context_properties(glx_context),
            CL_GLX_DISPLAY_KHR,  cl_context_properties(x_display),
            0};
}

bool device_drives_gl(const DeviceInfo& device, const std::vector<cl_context_properties>& properties) {
    // An extension function: reached through the platform, not linked.
    auto get_info = reinterpret_cast<clGetGLContextInfoKHR_fn>(
        clGetExtensionFunctionAddressForPlatform(device.platform, "clGetGLContextInfoKHR"));
    if (!get_info) return false;
    cl_device_id current = nullptr;
    if (get_info(properties.data(), CL_CURRENT_DEVICE_FOR_GL_CONTEXT_KHR, sizeof current, &current, nullptr) !=
        CL_SUCCESS)
        return false;
    return current == device.device;
}

GlSharedBuffer::GlSharedBuffer(Context& ctx, unsigned gl_buffer, std::size_t bytes) : ctx_(ctx) {
    cl_int err = CL_SUCCESS;
    cl_mem m = clCreateFromGLBuffer(ctx.get(), CL_MEM_WRITE_ONLY, gl_buffer, &err);
    cl_check(err, "clCreateFromGLBuffer");
    mem_ = Buffer(m, bytes);
}

void GlSharedBuffer::copy_from(const Buffer& src) {
    cl_mem m = mem_.get();
    cl_command_queue q = ctx_.queue();
    cl_check(clEnqueueAcquireGLObjects(q, 1, &m, 0, nullptr, nullptr), "clEnqueueAcquireGLObjects");
    const std::size_t bytes = std::min(src.bytes(), mem_.bytes());
    const cl_int copied = clEnqueueCopyBuffer(q, src.get(), m, 0, 0, bytes, 0, nullptr, nullptr);
    // Release even when the copy failed, so GL is not left locked out.
    cl_check(clEnqueueReleaseGLObjects(q, 1, &m, 0, nullptr, nullptr), "clEnqueueReleaseGLObjects");
    cl_check(copied, "clEnqueueCopyBuffer into the shared GL buffer");
    cl_check(clFinish(q), "clFinish after the GL copy");
}

}  // namespace clpath
