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
        compiled(wf, "sm_90", {uses("wf_shade", 64, 0), uses("wf_trace", 64, 248), uses("wf_light", 64, 0),
                               uses("wf_connect", 64, 0), uses("wf_scatter", 64, 0)}),
        compiled(wf_gltf, "sm_90", {uses("wf_shade", 96, 0), uses("wf_connect", 96, 0), uses("wf_scatter", 96, 0)}),
        compiled(rays, "gfx90a", {uses("batch_trace_closest", 120, 400)}),  // budgets are sm_90's
    };
    EXPECT_TRUE(budget_violations(within).empty());
    EXPECT_TRUE(budget_shortfalls(within).empty());
    const std::vector<ProgramCompile> over = {
        compiled(rays, "sm_90", {uses("batch_trace_any", 65, 0)}),
        compiled(wf, "sm_90", {uses("wf_camera", 65, 0), uses("wf_accumulate", 40, 264), uses("wf_shade", 65, 0)}),
        compiled(wf_gltf, "sm_90", {uses("wf_shade", 97, 0), uses("wf_light", 65, 0), uses("wf_scatter", 97, 0)}),
    };
    const auto v = budget_violations(over);
    ASSERT_EQ(v.size(), 7u);
    EXPECT_EQ(v[0], "rays-bvh batch_trace_any sm_90: 65 registers > 64");
    EXPECT_EQ(v[1], "wf-path wf_camera sm_90: 65 registers > 64");
    EXPECT_EQ(v[2], "wf-path wf_accumulate sm_90: 264 B stack > 256");
    EXPECT_EQ(v[3], "wf-path wf_shade sm_90: 65 registers > 64");
    EXPECT_EQ(v[4], "wf-path-gltf wf_shade sm_90: 97 registers > 96");
    EXPECT_EQ(v[5], "wf-path-gltf wf_light sm_90: 65 registers > 64");
    EXPECT_EQ(v[6], "wf-path-gltf wf_scatter sm_90: 97 registers > 96");
    EXPECT_TRUE(budget_shortfalls(over).empty());
}

// A kernel not yet within its budget is an open shortfall up to the figures
// it is held at, and a violation past them.
TEST(KernelBudgets, HeldKernelsFailPastTheirHeldFigures) {
    int held = 0;
    for (const KernelBudget& b : kernel_budgets()) {
        if (b.held_registers == 0 && b.held_stack_bytes == 0) continue;
        ++held;
        SCOPED_TRACE(b.kernel);
        // What is held is held above the budget; what is not is the budget itself.
        const bool regs = b.held_registers != 0, stack = b.held_stack_bytes != 0;
        if (regs) {
            ASSERT_GT(b.held_registers, b.max_registers);
        }
        if (stack) {
            ASSERT_GT(b.held_stack_bytes, b.max_stack_bytes);
        }
        const std::size_t n = std::size_t(regs) + std::size_t(stack);
        const int at_regs = regs ? b.held_registers : b.max_registers;
        const int at_stack = stack ? b.held_stack_bytes : b.max_stack_bytes;
        // A program the entry selects: its option where it names one.
        const std::string with = b.with_option ? std::string(" ") + b.with_option : std::string();
        const ProgramSpec p{"wf-held", {}, "-cl-std=CL1.2 -DCLP_HAS_MAT_DIFFUSE -DCLP_TARGET_GPU" + with, {}, ""};
        const std::vector<ProgramCompile> open = {compiled(p, b.target, {uses(b.kernel, at_regs, at_stack)})};
        EXPECT_TRUE(budget_violations(open).empty());
        EXPECT_EQ(budget_shortfalls(open).size(), n);
        const std::vector<ProgramCompile> past = {
            compiled(p, b.target, {uses(b.kernel, at_regs + (regs ? 1 : 0), at_stack + (stack ? 8 : 0))})};
        EXPECT_EQ(budget_violations(past).size(), n);
        EXPECT_TRUE(budget_shortfalls(past).empty());
        // Past the budget in what is not held, it fails.
        if (!stack) {
            const std::vector<ProgramCompile> deep = {compiled(p, b.target, {uses(b.kernel, at_regs, at_stack + 8)})};
            EXPECT_EQ(budget_violations(deep).size(), 1u);
        }
    }
    if (held == 0) GTEST_SKIP() << "every kernel is within its budget: none is held";
}

// A hold naming several options holds only programs with all of them: with
// one of them alone, the budget for any program applies.
TEST(KernelBudgets, AHeldCombinationHoldsOnlyTheCombination) {
    int combinations = 0;
    for (const KernelBudget& b : kernel_budgets()) {
        if (b.held_registers == 0 || !b.with_option) continue;
        const std::string with = b.with_option;
        if (with.find(' ') == std::string::npos) continue;
        ++combinations;
        SCOPED_TRACE(b.kernel);
        const std::string base = "-cl-std=CL1.2 -DCLP_HAS_MAT_DIFFUSE -DCLP_TARGET_GPU ";
        const ProgramSpec all{"wf-held", {}, base + with, {}, ""};
        const ProgramSpec one{"wf-one", {}, base + with.substr(0, with.find(' ')), {}, ""};
        EXPECT_TRUE(budget_violations({compiled(all, b.target, {uses(b.kernel, b.held_registers, 0)})}).empty());
        EXPECT_EQ(budget_violations({compiled(one, b.target, {uses(b.kernel, b.held_registers, 0)})}).size(), 1u);
    }
    if (combinations == 0) GTEST_SKIP() << "no held combination of options";
}

TEST(KernelBudgets, CpuCodeIsNotHeldToThem) {
    ProgramSpec cpu{"rays-bvh", {}, "-cl-std=CL1.2", {}, ""};
    EXPECT_TRUE(budget_violations({compiled(cpu, "sm_90", {uses("batch_trace_closest", 95, 544)})}).empty());
}
