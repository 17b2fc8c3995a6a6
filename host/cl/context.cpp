#include "cl/context.hpp"

#include <algorithm>
#include <cstdlib>
#include <sstream>

#include "cl/huge_pages.hpp"
#include "util/env_values.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

void CL_CALLBACK free_host_copy(cl_mem, void* p) { free_huge_copy(p); }

// CLPATH_HUGE_PAGES=0 keeps every buffer a device copy (to measure the difference).
bool huge_pages_wanted() { return env_whole_number("CLPATH_HUGE_PAGES", 0, 1, "(0 or 1)").value_or(1) == 1; }

std::string mib(std::size_t bytes) {
    std::ostringstream os;
    os.precision(4);
    os << double(bytes) / (1 << 20) << " MiB";
    return os.str();
}

}  // namespace

Context::Context(const DeviceInfo& device) : device_(device) {
    // A bad value is refused before any work, not when the first buffer is made.
    env_whole_number("CLPATH_DEVICE_MEMORY_LIMIT", 1, UINT64_MAX, "bytes");
    huge_pages_ = huge_pages_wanted();
    cl_int err = CL_SUCCESS;
    ctx_ = clCreateContext(nullptr, 1, &device_.device, nullptr, nullptr, &err);
    cl_check(err, "clCreateContext on " + device_.name);
    queue_ = clCreateCommandQueue(ctx_, device_.device, CL_QUEUE_PROFILING_ENABLE, &err);
    if (err != CL_SUCCESS) {
        clReleaseContext(ctx_);
        cl_check(err, "clCreateCommandQueue on " + device_.name);
    }
}

Context::Context(const DeviceInfo& device, const std::vector<cl_context_properties>& properties) : device_(device) {
    env_whole_number("CLPATH_DEVICE_MEMORY_LIMIT", 1, UINT64_MAX, "bytes");
    huge_pages_ = huge_pages_wanted();
    cl_int err = CL_SUCCESS;
    ctx_ = clCreateContext(properties.empty() ? nullptr : properties.data(), 1, &device_.device, nullptr, nullptr, &err);
    cl_check(err, "clCreateContext (with properties) on " + device_.name);
    queue_ = clCreateCommandQueue(ctx_, device_.device, CL_QUEUE_PROFILING_ENABLE, &err);
    if (err != CL_SUCCESS) {
        clReleaseContext(ctx_);
        cl_check(err, "clCreateCommandQueue on " + device_.name);
    }
}

Context::~Context() {
    if (queue_) {
        clFinish(queue_);
        clReleaseCommandQueue(queue_);
    }
    if (ctx_) clReleaseContext(ctx_);
}

void Context::check_fits(const std::vector<std::pair<std::string, std::size_t>>& buffers) const {
    // CLPATH_DEVICE_MEMORY_LIMIT (bytes) makes the device look smaller, so that
    // refusing a scene too large for it can be tested on any machine.
    std::size_t max_alloc = device_.max_alloc, global_mem = device_.global_mem;
    std::string limited;
    if (const auto env = env_whole_number("CLPATH_DEVICE_MEMORY_LIMIT", 1, UINT64_MAX, "bytes")) {
        const std::size_t limit = std::size_t(*env);
        max_alloc = std::min(max_alloc, limit);
        global_mem = std::min(global_mem, limit);
        limited = " (limited by CLPATH_DEVICE_MEMORY_LIMIT)";
    }
    std::size_t total = *allocated_;
    for (const auto& [what, bytes] : buffers) {
        if (bytes > max_alloc)
            throw Error(what + " needs " + mib(bytes) + ", more than " + device_.name +
                        " allows in one buffer (CL_DEVICE_MAX_MEM_ALLOC_SIZE = " + mib(max_alloc) + ")" + limited);
        total += bytes;
    }
    if (total > global_mem)
        throw Error("the scene's buffers need " + mib(total) + " in all, more than the " + mib(global_mem) +
                    " of global memory of " + device_.name + limited);
}

Buffer Context::buffer(std::size_t bytes, cl_mem_flags flags, const std::string& what, const void* init) {
    if (bytes == 0) bytes = 16;  // OpenCL forbids empty buffers; a kernel never reads this one
    check_fits({{what, bytes}});
    cl_int err = CL_SUCCESS;
    cl_mem m = nullptr;
    // A large read-only buffer on a CPU device is read in place from memory
    // on huge pages (cl/huge_pages.hpp): the scene's nodes and triangles.
    if (huge_pages_ && init && device_.is_cpu && flags == CL_MEM_READ_ONLY && bytes >= kHugePageBytes)
        if (void* host = huge_copy(init, bytes)) {
            m = clCreateBuffer(ctx_, CL_MEM_READ_ONLY | CL_MEM_USE_HOST_PTR, bytes, host, &err);
            if (err != CL_SUCCESS || clSetMemObjectDestructorCallback(m, free_host_copy, host) != CL_SUCCESS) {
                if (m) clReleaseMemObject(m);  // then the ordinary copy below, after the device is done with it
                m = nullptr;
                if (err != CL_SUCCESS) free_huge_copy(host);
            }
        }
    if (!m) m = clCreateBuffer(ctx_, flags | (init ? CL_MEM_COPY_HOST_PTR : 0), bytes, const_cast<void*>(init), &err);
    cl_check(err, "allocating " + what + " (" + mib(bytes) + ") on " + device_.name);
    *allocated_ += bytes;
    if (init) to_device_ += bytes;
    return Buffer(m, bytes, allocated_);
}

void Context::write(const Buffer& b, const void* data, std::size_t bytes, std::size_t offset) {
    cl_check(clEnqueueWriteBuffer(queue_, b.get(), CL_TRUE, offset, bytes, data, 0, nullptr, nullptr),
             "clEnqueueWriteBuffer");
    to_device_ += bytes;
}

cl_event Context::write_async(const Buffer& b, const void* data, std::size_t bytes, bool want_event) {
    cl_event e = nullptr;
    cl_check(clEnqueueWriteBuffer(queue_, b.get(), CL_FALSE, 0, bytes, data, 0, nullptr, want_event ? &e : nullptr),
             "clEnqueueWriteBuffer");
    to_device_ += bytes;
    return e;
}

cl_event Context::read_async(const Buffer& b, void* data, std::size_t bytes, bool want_event) {
    cl_event e = nullptr;
    cl_check(clEnqueueReadBuffer(queue_, b.get(), CL_FALSE, 0, bytes, data, 0, nullptr, want_event ? &e : nullptr),
             "clEnqueueReadBuffer");
    from_device_ += bytes;
    return e;
}

void Context::fill_async(const Buffer& b, cl_uint word) {
    // The pattern is copied at the call (OpenCL 1.2, clEnqueueFillBuffer).
    cl_check(clEnqueueFillBuffer(queue_, b.get(), &word, sizeof word, 0, b.bytes(), 0, nullptr, nullptr),
             "clEnqueueFillBuffer");
}

void Context::read(const Buffer& b, void* data, std::size_t bytes, std::size_t offset) {
    cl_check(clEnqueueReadBuffer(queue_, b.get(), CL_TRUE, offset, bytes, data, 0, nullptr, nullptr),
             "clEnqueueReadBuffer");
    from_device_ += bytes;
}

void Context::zero(const Buffer& b) {
    const cl_uint word = 0;
    const std::size_t pattern = b.bytes() % sizeof word == 0 ? sizeof word : 1;
    cl_check(clEnqueueFillBuffer(queue_, b.get(), &word, pattern, 0, b.bytes(), 0, nullptr, nullptr),
             "clEnqueueFillBuffer");
    finish();
}

Kernel Context::kernel(cl_program program, const std::string& name) {
    cl_int err = CL_SUCCESS;
    cl_kernel k = clCreateKernel(program, name.c_str(), &err);
    cl_check(err, "clCreateKernel(" + name + ")");
    return Kernel(k, name);
}

cl_event Context::launch(const Kernel& k, std::size_t global, std::size_t local, bool want_event) {
    if (global == 0) return nullptr;
    std::size_t g = global;
    if (local) g = (global + local - 1) / local * local;
    cl_event ev = nullptr;
    cl_check(clEnqueueNDRangeKernel(queue_, k.get(), 1, nullptr, &g, local ? &local : nullptr, 0, nullptr,
                                    want_event ? &ev : nullptr),
             "launching " + k.name() + " on " + device_.name);
    return ev;
}

void Context::finish() { cl_check(clFinish(queue_), "clFinish on " + device_.name); }

double event_seconds(cl_event e) {
    cl_ulong start = 0, end = 0;
    cl_check(clWaitForEvents(1, &e), "clWaitForEvents");
    cl_check(clGetEventProfilingInfo(e, CL_PROFILING_COMMAND_START, sizeof start, &start, nullptr),
             "clGetEventProfilingInfo");
    cl_check(clGetEventProfilingInfo(e, CL_PROFILING_COMMAND_END, sizeof end, &end, nullptr),
             "clGetEventProfilingInfo");
    clReleaseEvent(e);
    return double(end - start) * 1e-9;
}

double event_span_seconds(cl_event first, cl_event last) {
    cl_ulong start = 0, end = 0;
    cl_check(clWaitForEvents(1, &last), "clWaitForEvents");
    cl_check(clGetEventProfilingInfo(first, CL_PROFILING_COMMAND_START, sizeof start, &start, nullptr),
             "clGetEventProfilingInfo");
    cl_check(clGetEventProfilingInfo(last, CL_PROFILING_COMMAND_END, sizeof end, &end, nullptr),
             "clGetEventProfilingInfo");
    clReleaseEvent(first);
    clReleaseEvent(last);
    return end > start ? double(end - start) * 1e-9 : 0.0;
}

}  // namespace clpath
