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

cl_program test_program(const std::string& root, const std::string& options) {
    // Built on first use; the device first, so that the programs are
    // released before its context.
    Context& ctx = device();
    static std::map<std::pair<std::string, std::string>, Program> programs;
    const auto key = std::make_pair(root, options);
    auto it = programs.find(key);
    if (it == programs.end())
        it = programs.emplace(key, build_program(ctx, program_source({root}, test_kernel_sources()), options).program)
                 .first;
    return it->second.get();
}

cl_program probe_program(const RenderSettings& settings) {
    RenderSettings all = settings;
    // Every feature compiled in, so probes reach every material and light kind.
    all.all_features = true;
    return test_program("probes.cl", build_options(kernel_features(SceneFeatures{}, all)));
}

cl_program probe_program() { return probe_program(RenderSettings{}); }

void run(const Kernel& k, std::size_t n) {
    device().launch(k, n, 0);
    device().finish();
}

}  // namespace clpath::test
