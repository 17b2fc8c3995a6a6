#include "support/test_device.hpp"

#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>

#include "cl/embedded_sources.hpp"
#include "render/kernel_features.hpp"
#include "render/kernel_programs.hpp"
#include "util/error.hpp"

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

NodeLayout node_layout() {
    static const NodeLayout layout = [] {
        const char* e = std::getenv("CLPATH_TEST_NODES");
        if (e && std::string(e) == "bvh4") return NodeLayout::Bvh4;
        if (e && std::string(e) == "bvh8") return NodeLayout::Bvh8;
        if (e && *e) throw Error(std::string("CLPATH_TEST_NODES=") + e + ": choose bvh4 or bvh8");
        return clpath::node_layout(kernel_code(device().device()), false);
    }();
    return layout;
}

cl_program probe_program(const RenderSettings& settings) {
    RenderSettings all = settings;
    // Every feature compiled in, so probes reach every material and light kind.
    all.all_features = true;
    return test_program("probes.cl", build_options(kernel_features(SceneFeatures{}, all)) + layout_options(node_layout()));
}

cl_program probe_program() { return probe_program(RenderSettings{}); }

void run(const Kernel& k, std::size_t n) {
    device().launch(k, n, 0);
    device().finish();
}

}  // namespace clpath::test
