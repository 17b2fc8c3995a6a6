// clpath's own batch kernels, run in the harness's process beside tinybvh's
// (--paired): from what clpath bench rays --save-rays DIR wrote beside the
// rays (the program's source and options, the node and triangle buffers;
// host/bench/ray_files.hpp in clpath), so that the two can be launched
// alternately on the same device, launch by launch. On a machine whose speed
// drifts by more than the difference measured, two processes run one after
// the other cannot be compared; launches taken turn about can.
#pragma once
#include <cmath>
#include <iterator>
#include <memory>
#include <string>

#include "harness_common.hpp"

namespace harness {

inline std::string read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Fail(path + ": cannot open (clpath bench rays --save-rays writes it beside the rays)");
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The program and the structure, once per scene.
class ClpathProgram {
public:
    ClpathProgram(const Cl& cl, const std::string& dir) {
        const std::string source = read_file(dir + "/batch_kernels.cl");
        std::string options = read_file(dir + "/batch_kernels.options");
        while (!options.empty() && (options.back() == '\n' || options.back() == '\r')) options.pop_back();
        const std::string nodes = read_file(dir + "/nodes.bin"), tris = read_file(dir + "/triangles.bin");
        // Nodes of 128 bytes (4-wide) or 256 (8-wide, what CPU programs walk): whole multiples of 128 either way.
        if (nodes.empty() || nodes.size() % 128 || tris.empty() || tris.size() % 48)
            throw Fail(dir + ": nodes.bin or triangles.bin is not whole nodes (128 or 256 bytes) and 48-byte triangles");
        cl_int e;
        const char* src = source.c_str();
        program_ = clCreateProgramWithSource(cl.context, 1, &src, nullptr, &e);
        check(e, "clCreateProgramWithSource (clpath's batch kernels)");
        if (clBuildProgram(program_, 1, &cl.device, options.c_str(), nullptr, nullptr) != CL_SUCCESS)
            throw Fail(dir + "/batch_kernels.cl: clpath's batch kernels did not build with '" + options + "'");
        nodes_ = std::make_unique<Mem>(cl, nodes.size(), nodes.data());
        tris_ = std::make_unique<Mem>(cl, tris.size(), tris.data());
        triangles_ = tris.size() / 48;
        options_ = options;
    }
    ~ClpathProgram() {
        if (program_) clReleaseProgram(program_);
    }
    ClpathProgram(const ClpathProgram&) = delete;
    ClpathProgram& operator=(const ClpathProgram&) = delete;
    cl_program program() const { return program_; }
    const Mem& nodes() const { return *nodes_; }
    const Mem& triangles() const { return *tris_; }
    std::size_t triangle_count() const { return triangles_; }
    const std::string& options() const { return options_; }

private:
    cl_program program_ = nullptr;
    std::unique_ptr<Mem> nodes_, tris_;
    std::size_t triangles_ = 0;
    std::string options_;
};

// One batch: its rays on the device and the kernel that traces them.
class ClpathBatch {
public:
    ClpathBatch(const Cl& cl, const ClpathProgram& p, const RayBatch& b, std::size_t workgroup)
        : cl_(cl), n_(b.rays.size()), any_(b.any_hit), wg_(workgroup) {
        // A saved record is a BatchRay (o, tmax, d, then a field the kernels do not read).
        rays_ = std::make_unique<Mem>(cl, n_ * sizeof(SavedRay), b.rays.data());
        out_ = std::make_unique<Mem>(cl, n_ * (any_ ? 4 : 16), nullptr);
        cl_int e;
        k_ = clCreateKernel(p.program(), any_ ? "batch_trace_any" : "batch_trace_closest", &e);
        check(e, "clCreateKernel (clpath's batch kernels)");
        const cl_uint count = cl_uint(n_);
        check(clSetKernelArg(k_, 0, sizeof(cl_mem), &p.nodes().m), "clSetKernelArg");
        check(clSetKernelArg(k_, 1, sizeof(cl_mem), &p.triangles().m), "clSetKernelArg");
        check(clSetKernelArg(k_, 2, sizeof(cl_mem), &rays_->m), "clSetKernelArg");
        check(clSetKernelArg(k_, 3, sizeof(cl_mem), &out_->m), "clSetKernelArg");
        check(clSetKernelArg(k_, 4, sizeof count, &count), "clSetKernelArg");
    }
    ~ClpathBatch() { clReleaseKernel(k_); }
    ClpathBatch(const ClpathBatch&) = delete;
    ClpathBatch& operator=(const ClpathBatch&) = delete;

    double launch() { return launch_ms(cl_, k_, n_, wg_); }

    // Rays whose answer now differs from the one clpath saved (bit for bit:
    // the same kernels on the same device must give the same answers).
    std::size_t differs_from_saved(const RayBatch& b) const {
        std::vector<std::int32_t> out(n_ * (any_ ? 1 : 4));
        check(clEnqueueReadBuffer(cl_.queue, out_->m, CL_TRUE, 0, out.size() * 4, out.data(), 0, nullptr, nullptr),
              "clEnqueueReadBuffer (clpath's answers)");
        std::size_t d = 0;
        for (std::size_t i = 0; i < n_; ++i) {
            float now;
            if (any_) {
                now = out[i] >= 0 ? 1.0f : 0.0f;
            } else {  // Hit: t, b1, b2, tri (-1: a miss, saved as +infinity)
                std::memcpy(&now, &out[4 * i], 4);
                if (out[4 * i + 3] < 0) now = INFINITY;
            }
            d += std::memcmp(&now, &b.rays[i].result, 4) != 0;
        }
        return d;
    }

private:
    const Cl& cl_;
    std::size_t n_;
    bool any_;
    std::size_t wg_;
    std::unique_ptr<Mem> rays_, out_;
    cl_kernel k_ = nullptr;
};

}  // namespace harness
