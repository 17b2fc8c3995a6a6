// The offline GPU compile's parsers (cl/offline_compile.hpp): ptxas -v's
// report, the AMDGPU kernel metadata and llvm-nm's undefined symbols, on
// output of the kind the tools print; no toolchain needed.
#include <gtest/gtest.h>

#include "cl/offline_compile.hpp"

using namespace clpath;

TEST(OfflineCompile, PtxasReportGivesEachEntryItsOwnFigures) {
    // A called function's properties come between and must not be taken for a kernel's.
    const std::string text =
        "ptxas info    : 0 bytes gmem\n"
        "ptxas info    : Function properties for normalize_builtin\n"
        "    16 bytes stack frame, 0 bytes spill stores, 0 bytes spill loads\n"
        "ptxas info    : Compiling entry function 'batch_trace_any' for 'sm_90'\n"
        "ptxas info    : Function properties for batch_trace_any\n"
        "    248 bytes stack frame, 8 bytes spill stores, 4 bytes spill loads\n"
        "ptxas info    : Used 59 registers, used 0 barriers, 264 bytes cumulative stack size\n"
        "ptxas info    : Compile time = 150.0 ms\n"
        "ptxas info    : Function properties for normalize_builtin\n"
        "    0 bytes stack frame, 0 bytes spill stores, 0 bytes spill loads\n"
        "ptxas info    : Compiling entry function 'batch_primary_rays' for 'sm_90'\n"
        "ptxas info    : Function properties for batch_primary_rays\n"
        "    0 bytes stack frame, 0 bytes spill stores, 0 bytes spill loads\n"
        "ptxas info    : Used 22 registers, used 0 barriers\n";
    const auto k = parse_ptxas_report(text);
    ASSERT_EQ(k.size(), 2u);
    EXPECT_EQ(k[0].kernel, "batch_trace_any");
    EXPECT_EQ(k[0].registers, 59);
    EXPECT_EQ(k[0].stack_bytes, 264);  // cumulative: with what it calls
    EXPECT_EQ(k[0].spill_bytes, 12);
    EXPECT_EQ(k[1].kernel, "batch_primary_rays");
    EXPECT_EQ(k[1].registers, 22);
    EXPECT_EQ(k[1].stack_bytes, 0);
}

TEST(OfflineCompile, AmdMetadataGivesEachKernelItsOwnFigures) {
    // Argument entries have .name keys too, indented deeper: they are not kernels.
    const std::string s =
        "\t.text\n"
        "\t.amdgpu_metadata\n"
        "---\n"
        "amdhsa.kernels:\n"
        "  - .args:\n"
        "      - .address_space:  global\n"
        "        .name:           nodes\n"
        "        .offset:         0\n"
        "    .group_segment_fixed_size: 0\n"
        "    .name:           batch_trace_closest\n"
        "    .private_segment_fixed_size: 248\n"
        "    .sgpr_count:     67\n"
        "    .sgpr_spill_count: 2\n"
        "    .vgpr_count:     102\n"
        "    .vgpr_spill_count: 5\n"
        "  - .args:\n"
        "      - .name:           out\n"
        "    .name:           film_resolve\n"
        "    .private_segment_fixed_size: 0\n"
        "    .sgpr_count:     14\n"
        "    .vgpr_count:     22\n"
        "amdhsa.target:   amdgcn-amd-amdhsa--gfx90a\n"
        "...\n"
        "\t.end_amdgpu_metadata\n";
    const auto k = parse_amdgpu_metadata(s);
    ASSERT_EQ(k.size(), 2u);
    EXPECT_EQ(k[0].kernel, "batch_trace_closest");
    EXPECT_EQ(k[0].registers, 102);
    EXPECT_EQ(k[0].sgprs, 67);
    EXPECT_EQ(k[0].stack_bytes, 248);
    EXPECT_EQ(k[0].spill_bytes, 7);
    EXPECT_EQ(k[1].kernel, "film_resolve");
    EXPECT_EQ(k[1].registers, 22);
    EXPECT_TRUE(parse_amdgpu_metadata("no metadata here").empty());
}

TEST(OfflineCompile, UndefinedSymbolsLeaveOutIntrinsics) {
    const auto u = parse_undefined_symbols("                 U occlude_tree\n"
                                           "                 U llvm.nvvm.read.ptx.sreg.tid.x\n"
                                           "0000000000000000 T batch_trace_any\n"
                                           "                 U traverse_tree\n");
    ASSERT_EQ(u.size(), 2u);
    EXPECT_EQ(u[0], "occlude_tree");
    EXPECT_EQ(u[1], "traverse_tree");
    EXPECT_TRUE(parse_undefined_symbols("").empty());
}

TEST(OfflineCompile, MissingToolsAreNamedPerTarget) {
    OfflineToolchain none;
    none.libclc_dir = "/no/such/folder";
    const std::string nv = missing_tools(none, "sm_90"), amd = missing_tools(none, "gfx1100");
    EXPECT_NE(nv.find("clang-14"), std::string::npos);
    EXPECT_NE(nv.find("ptxas"), std::string::npos);
    EXPECT_NE(nv.find("libclc"), std::string::npos);
    EXPECT_NE(amd.find("clang-15"), std::string::npos);
    EXPECT_EQ(amd.find("ptxas"), std::string::npos);
    const OfflineResult r = compile_offline(none, "gfx90a", "kernel void k() {}", "-cl-std=CL1.2", "/tmp/unused");
    EXPECT_FALSE(r.ok);
    EXPECT_NE(r.log.find("missing"), std::string::npos);
}
