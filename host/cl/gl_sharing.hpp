#pragma once
// OpenCL/OpenGL sharing (cl_khr_gl_sharing) through GLX: a context tied to
// the current GL context, and a GL buffer that kernels' results are copied
// into without passing through the host. Nothing here calls OpenGL itself
// (the core library links no GL): the caller passes the GLX handles.
#include <CL/cl.h>

#include <string>
#include <vector>

#include "cl/context.hpp"

namespace clpath {

bool has_gl_sharing(const DeviceInfo& device);

// Properties for a context shared with a GLX context: platform, GL context,
// X display, zero-terminated.
std::vector<cl_context_properties> glx_sharing_properties(const DeviceInfo& device, void* glx_context,
                                                          void* x_display);

// Whether device is the one that drives that GL context (a context may only
// share with the GPU the GL context runs on). Errors count as "no".
bool device_drives_gl(const DeviceInfo& device, const std::vector<cl_context_properties>& properties);

// A GL buffer object seen from OpenCL. Each copy acquires it, copies a device
// buffer into it and releases it, and waits, so GL may read it afterwards.
class GlSharedBuffer {
public:
    GlSharedBuffer(Context& ctx, unsigned gl_buffer, std::size_t bytes);
    void copy_from(const Buffer& src);

private:
    Context& ctx_;
    Buffer mem_;
};

}  // namespace clpath
