// program_source (host/cl/embedded_sources.hpp): the one function that turns
// the embedded kernel files and their #includes into a program.
#include <gtest/gtest.h>

#include <regex>
#include <string>

#include "cl/embedded_sources.hpp"
#include "support/test_device.hpp"
#include "util/error.hpp"

using namespace clpath;

namespace {

// How many times file's text starts in the assembled source.
int starts(const std::string& src, const std::string& file) {
    const std::string mark = "#line 1 \"" + file + "\"\n";
    int n = 0;
    for (std::size_t at = src.find(mark); at != std::string::npos; at = src.find(mark, at + 1)) ++n;
    return n;
}

bool has_quoted_include(const std::string& src) {
    static const std::regex include(R"re((^|\n)\s*#\s*include\s*")re");
    return std::regex_search(src, include);
}

}  // namespace

TEST(ProgramAssembly, EveryKernelFileIsTakenOnceWithWhatItIncludes) {
    const std::string src = program_source(renderer_kernel_files());
    EXPECT_FALSE(has_quoted_include(src));
    for (const char* f : {"shared_structs.h", "common.h", "rng.cl", "sampling.cl", "camera.cl", "intersect.cl",
                          "traverse.cl", "materials.cl", "lights.cl", "film.cl", "integrator.cl"})
        EXPECT_EQ(starts(src, f), 1) << f;
    // What a file includes comes before the code that follows the #include.
    EXPECT_LT(src.find("#line 1 \"shared_structs.h\""), src.find("inline float3 load3("));
    EXPECT_LT(src.find("#line 1 \"intersect.cl\""), src.find("inline void traverse_bvh("));
    EXPECT_EQ(starts(src, "ray_batches.cl"), 0);
}

TEST(ProgramAssembly, RootsThatShareFilesTakeThemOnce) {
    const std::string src = program_source({"ray_batches.cl", "integrator.cl"});
    EXPECT_EQ(starts(src, "traverse.cl"), 1);
    EXPECT_EQ(starts(src, "ray_batches.cl"), 1);
    EXPECT_EQ(starts(src, "integrator.cl"), 1);
}

// After an #include, the including file's line numbers resume where they were.
TEST(ProgramAssembly, LineNumbersResumeAfterAnInclude) {
    const SourceTable extra = {{"a_test.cl", "// one\n#include \"common.h\"\nint three;\n"}};
    const std::string src = program_source({"a_test.cl"}, extra);
    const std::size_t common = src.find("#line 1 \"common.h\"");
    ASSERT_NE(common, std::string::npos);
    EXPECT_NE(src.find("#line 3 \"a_test.cl\"\nint three;\n", common), std::string::npos);
}

TEST(ProgramAssembly, AMissingFileIsAnErrorNamingBothFiles) {
    const SourceTable extra = {{"b_test.cl", "#include \"common.h\"\n#include \"no_such.h\"\n"}};
    try {
        program_source({"b_test.cl"}, extra);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("no_such.h (included from b_test.cl:2) is not embedded"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_THROW(program_source({"no_such_root.cl"}), Error);
    const SourceTable clash = {{"rng.cl", ""}};
    EXPECT_THROW(program_source({"rng.cl"}, clash), Error);
}

// Test probes are embedded in the test programs only, never in the binary users run.
TEST(ProgramAssembly, TestKernelsAreNotInTheShippedTable) {
    ASSERT_FALSE(test_kernel_sources().empty());
    for (const auto& t : test_kernel_sources())
        for (const auto& s : embedded_sources()) EXPECT_STRNE(t.name, s.name);
    for (const auto& s : embedded_sources()) {
        const std::string name = s.name;
        EXPECT_EQ(name.find("probe"), std::string::npos) << name;
    }
}
