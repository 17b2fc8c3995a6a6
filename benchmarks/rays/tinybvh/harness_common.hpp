// What the side-by-side harness's two runners share: the ray files clpath
// bench rays --save-rays writes (format: host/bench/ray_files.hpp in clpath)
// and a little plain OpenCL (device, buffers, one timed launch). Our code.
#pragma once
#define CL_TARGET_OPENCL_VERSION 300
#include <CL/cl.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace harness {

struct Fail : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// ---- the ray files (format: host/bench/ray_files.hpp in clpath) -----------

struct SavedRay {
    float o[3], tmax, d[3], result;
};
static_assert(sizeof(SavedRay) == 32, "ray record is 32 bytes");

struct RayBatch {
    std::string name;
    bool any_hit = false;
    std::vector<SavedRay> rays;
};

inline std::uint32_t le32(const unsigned char* p) { return p[0] | p[1] << 8 | p[2] << 16 | std::uint32_t(p[3]) << 24; }

inline RayBatch read_rays(const std::string& path, const std::string& name) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Fail(path + ": cannot open (run clpath bench rays --save-rays first)");
    unsigned char h[32];
    if (!in.read(reinterpret_cast<char*>(h), 32)) throw Fail(path + ": shorter than its 32-byte header");
    if (std::memcmp(h, "CLPRAYS1", 8) != 0) throw Fail(path + ": not a clpath ray file (magic)");
    const std::uint32_t kind = le32(h + 8), query = le32(h + 12), lo = le32(h + 16), hi = le32(h + 20),
                        record = le32(h + 24);
    if (kind > 2 || query > 1 || record != 32 || hi != 0) throw Fail(path + ": unsupported header");
    static const char* names[] = {"primary", "shadow", "diffuse"};
    if (name != names[kind]) throw Fail(path + ": holds the " + names[kind] + " batch, expected " + name);
    RayBatch b;
    b.name = name;
    b.any_hit = query == 1;
    b.rays.resize(lo);
    if (!in.read(reinterpret_cast<char*>(b.rays.data()), std::streamsize(lo) * 32) || in.peek() != EOF)
        throw Fail(path + ": length does not match its " + std::to_string(lo) + " rays");
    return b;  // records are little-endian floats, as this x86-64 host reads them
}

// ---- OpenCL ----------------------------------------------------------------

inline void check(cl_int e, const char* what) {
    if (e != CL_SUCCESS) throw Fail(std::string("OpenCL: ") + what + " failed (" + std::to_string(e) + ")");
}

inline std::string device_info(cl_device_id d, cl_device_info what) {
    std::size_t n = 0;
    clGetDeviceInfo(d, what, 0, nullptr, &n);
    std::string s(n, '\0');
    clGetDeviceInfo(d, what, n, s.data(), nullptr);
    while (!s.empty() && s.back() == '\0') s.pop_back();
    return s;
}

struct Cl {
    cl_device_id device = nullptr;
    cl_context context = nullptr;
    cl_command_queue queue = nullptr;
    cl_program program = nullptr;
    std::string name;
    ~Cl() {
        if (program) clReleaseProgram(program);
        if (queue) clReleaseCommandQueue(queue);
        if (context) clReleaseContext(context);
    }
};

// The first device whose name holds `want` (any device when empty), over all platforms.
inline void open_device(Cl& cl, const std::string& want) {
    cl_uint np = 0;
    clGetPlatformIDs(0, nullptr, &np);
    std::vector<cl_platform_id> ps(np);
    if (np) clGetPlatformIDs(np, ps.data(), nullptr);
    for (cl_platform_id p : ps) {
        cl_uint nd = 0;
        if (clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, 0, nullptr, &nd) != CL_SUCCESS) continue;
        std::vector<cl_device_id> ds(nd);
        clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, nd, ds.data(), nullptr);
        for (cl_device_id d : ds) {
            const std::string name = device_info(d, CL_DEVICE_NAME);
            if (!want.empty() && name.find(want) == std::string::npos) continue;
            cl_int e;
            cl.device = d;
            cl.name = name;
            cl.context = clCreateContext(nullptr, 1, &d, nullptr, nullptr, &e);
            check(e, "clCreateContext");
            const cl_queue_properties props[] = {CL_QUEUE_PROPERTIES, CL_QUEUE_PROFILING_ENABLE, 0};
            cl.queue = clCreateCommandQueueWithProperties(cl.context, d, props, &e);
            check(e, "clCreateCommandQueueWithProperties");
            return;
        }
    }
    throw Fail("no OpenCL device" + (want.empty() ? std::string() : " whose name holds '" + want + "'"));
}

struct Mem {
    cl_mem m = nullptr;
    Mem(const Cl& cl, std::size_t bytes, const void* host) {
        cl_int e;
        m = clCreateBuffer(cl.context, CL_MEM_READ_WRITE | (host ? CL_MEM_COPY_HOST_PTR : 0), std::max<std::size_t>(bytes, 16),
                           const_cast<void*>(host), &e);
        check(e, "clCreateBuffer");
    }
    ~Mem() { clReleaseMemObject(m); }
    Mem(const Mem&) = delete;
    Mem& operator=(const Mem&) = delete;
};

// One launch over n work-items (the global size rounded up to the work-group),
// waited for; its device time in milliseconds, from profiling events.
inline double launch_ms(const Cl& cl, cl_kernel k, std::size_t n, std::size_t wg) {
    const std::size_t global = (n + wg - 1) / wg * wg;
    cl_event ev;
    check(clEnqueueNDRangeKernel(cl.queue, k, 1, nullptr, &global, &wg, 0, nullptr, &ev), "clEnqueueNDRangeKernel");
    check(clWaitForEvents(1, &ev), "clWaitForEvents");
    cl_ulong a = 0, b = 0;
    clGetEventProfilingInfo(ev, CL_PROFILING_COMMAND_START, sizeof a, &a, nullptr);
    clGetEventProfilingInfo(ev, CL_PROFILING_COMMAND_END, sizeof b, &b, nullptr);
    clReleaseEvent(ev);
    return double(b - a) * 1e-6;
}

}  // namespace harness
