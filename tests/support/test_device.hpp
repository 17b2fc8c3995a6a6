#pragma once
// The OpenCL device tests run on: $CLPATH_DEVICE if set, else the default
// choice (PoCL on a machine without a GPU, as in CI). One context per test program.
#include <string>
#include <vector>

#include "cl/context.hpp"
#include "cl/embedded_sources.hpp"
#include "cl/program.hpp"
#include "bvh/accel.hpp"
#include "render/settings.hpp"

namespace clpath {
// Generated from tests/*/*.cl and tests/kernels/*.h (tests/CMakeLists.txt).
const SourceTable& test_kernel_sources();
}

namespace clpath::test {

Context& device();

// A program built from one test kernel file (which #includes the kernel files
// it needs), once per test program and set of options.
cl_program test_program(const std::string& root, const std::string& options);

// The BVH node layout the test programs walk and device_nodes makes for
// them: $CLPATH_TEST_NODES (bvh4 or bvh8) if set, else what the renderer's
// programs walk on the test device (node_layout: bvh8 on PoCL's CPU device).
// CTest runs the traversal tests under both (tests/CMakeLists.txt).
NodeLayout node_layout();

// tests/kernels/probes.cl, built once per test program (for node_layout()).
cl_program probe_program();
// The same, built with the estimator choices of these settings (e.g. uniform
// hemisphere sampling); every feature is compiled in whatever they say.
cl_program probe_program(const RenderSettings& settings);

// Runs a kernel over n work-items and waits.
void run(const Kernel& k, std::size_t n);

template <class T, class A>
Buffer upload(const std::vector<T, A>& v, const std::string& what = "test input") {
    return device().buffer(v.size() * sizeof(T), CL_MEM_READ_WRITE, what, v.data());
}

template <class T>
std::vector<T> download(const Buffer& b, std::size_t n) {
    std::vector<T> v(n);
    device().read(b, v);
    return v;
}

}  // namespace clpath::test
