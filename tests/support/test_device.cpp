#include "support/test_device.hpp"

#include <cstdio>
#include <memory>

#include "cl/embedded_sources.hpp"
#include "render/kernel_features.hpp"

namespace clpath::test {

Context& device() {
    static std::unique_ptr<Context> ctx = [] {
        auto c = std::make_unique<Context>(select_device(""));
        std::fprintf(stderr, "[ device  ] %s\n", c->device().describe().c_str());
        return c;
    }();
    return *ctx;
}

cl_program probe_program() {
    static Program program = [] {
        auto files = renderer_kernel_files();
        files.push_back("probes.cl");
        // Every feature compiled in, so probes reach every material and light kind.
        RenderSettings all;
        all.all_features = true;
        return std::move(
            build_program(device(), program_source(files), build_options(kernel_features(SceneFeatures{}, all)))
                .program);
    }();
    return program.get();
}

void run(const Kernel& k, std::size_t n) {
    device().launch(k, n, 0);
    device().finish();
}

}  // namespace clpath::test
