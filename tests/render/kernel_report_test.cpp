// The portability gate's budgets (render/kernel_report.hpp): which kernels
// they hold, and that a kernel over one is reported.
#include "render/kernel_report.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace clpath;

namespace {

ProgramCompile compiled(const ProgramSpec& program, const std::string& target, std::vector<KernelResources> kernels) {
    ProgramCompile c;
    c.program = &program;
    c.result.target = target;
    c.result.ok = true;
    c.result.kernels = std::move(kernels);
    return c;
}

KernelResources uses(const std::string& kernel, int registers, int stack) {
    KernelResources k;
    k.kernel = kernel;
    k.registers = registers;
    k.stack_bytes = stack;
    return k;
}

}  // namespace

TEST(KernelBudgets, TraversalAndWavefrontKernelsOverTheirBudgetAreReported) {
    ProgramSpec rays{"rays-bvh", {}, "-cl-std=CL1.2 -DCLP_TARGET_GPU", {}, ""};
    ProgramSpec wf{"wf-path", {}, "-cl-std=CL1.2 -DCLP_HAS_MAT_DIFFUSE -DCLP_TARGET_GPU", {}, ""};
    ProgramSpec wf_gltf{"wf-path-gltf", {}, "-cl-std=CL1.2 -DCLP_HAS_MAT_GLTF -DCLP_TARGET_GPU", {}, ""};
    const std::vector<ProgramCompile> within = {
        compiled(rays, "sm_90", {uses("batch_trace_closest", 64, 256), uses("batch_primary_rays", 200, 512)}),
        compiled(wf, "sm_90", {uses("wf_shade", 64, 0), uses("wf_trace", 64, 248)}),
        compiled(wf_gltf, "sm_90", {uses("wf_shade", 96, 0)}),
        compiled(rays, "gfx90a", {uses("batch_trace_closest", 120, 400)}),  // budgets are sm_90's
    };
    EXPECT_TRUE(budget_violations(within).empty());
    const std::vector<ProgramCompile> over = {
        compiled(rays, "sm_90", {uses("batch_trace_any", 65, 0)}),
        compiled(wf, "sm_90", {uses("wf_shade", 65, 0), uses("wf_shadow", 40, 264)}),
        compiled(wf_gltf, "sm_90", {uses("wf_shade", 97, 0)}),
    };
    const auto v = budget_violations(over);
    ASSERT_EQ(v.size(), 4u);
    EXPECT_EQ(v[0], "rays-bvh batch_trace_any sm_90: 65 registers > 64");
    EXPECT_EQ(v[1], "wf-path wf_shade sm_90: 65 registers > 64");
    EXPECT_EQ(v[2], "wf-path wf_shadow sm_90: 264 B stack > 256");
    EXPECT_EQ(v[3], "wf-path-gltf wf_shade sm_90: 97 registers > 96");
}

TEST(KernelBudgets, CpuCodeIsNotHeldToThem) {
    ProgramSpec cpu{"rays-bvh", {}, "-cl-std=CL1.2", {}, ""};
    EXPECT_TRUE(budget_violations({compiled(cpu, "sm_90", {uses("batch_trace_closest", 95, 544)})}).empty());
}
