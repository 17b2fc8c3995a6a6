#include "support/test_device.hpp"

#include <cstdio>
#include <map>
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

cl_program probe_program(const RenderSettings& settings) {
    // One program per set of build options, built on first use; the device
    // first, so that the programs are released before its context.
    Context& ctx = device();
    static std::map<std::string, Program> programs;
    RenderSettings all = settings;
    // Every feature compiled in, so probes reach every material and light kind.
    all.all_features = true;
    const std::string options = build_options(kernel_features(SceneFeatures{}, all));
    auto it = programs.find(options);
    if (it == programs.end()) {
        auto files = renderer_kernel_files();
        files.push_back("probes.cl");
        it = programs.emplace(options, build_program(ctx, program_source(files), options).program).first;
    }
    return it->second.get();
}

cl_program probe_program() { return probe_program(RenderSettings{}); }

void run(const Kernel& k, std::size_t n) {
    device().launch(k, n, 0);
    device().finish();
}

}  // namespace clpath::test
