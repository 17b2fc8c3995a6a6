// The structs of kernels/shared_structs.h have the same layout on host and
// device: every field at the same offset with the same size, as the device
// compiler lays them out (probe_struct_layout), and no field left out of the
// list both sides read (tests/kernels/shared_struct_fields.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "kernels/shared_struct_fields.h"
#include "shared_structs.h"
#include "support/test_device.hpp"

using namespace clpath;

namespace {

struct Field {
    std::string name;
    std::uint32_t offset, size;
};

// offsetof of a struct that is not standard layout would be conditionally
// supported; these are plain C structs.
#define HOST_STRUCT(S) {#S, std::uint32_t(sizeof(S))},
#define HOST_FIELD(S, f) {#S, {#S "." #f, std::uint32_t(offsetof(S, f)), std::uint32_t(sizeof(S::f))}},

const std::vector<std::pair<std::string, std::uint32_t>> kHostStructs = {CLP_SHARED_STRUCTS(HOST_STRUCT)};
const std::vector<std::pair<std::string, Field>> kHostFields = {CLP_SHARED_FIELDS(HOST_FIELD)};

}  // namespace

TEST(SharedStructs, EveryFieldHasTheSameOffsetAndSizeOnHostAndDevice) {
    const std::size_t n = kHostStructs.size() + 2 * kHostFields.size();
    Kernel k = test::device().kernel(test::probe_program(), "probe_struct_layout");
    std::vector<std::uint32_t> fill(n + 1, 0xdeadbeefu);  // one past the end: the probe writes no more than listed
    Buffer out = test::upload(fill, "layout");
    k.arg(0, out);
    test::run(k, 1);
    const auto dev = test::download<std::uint32_t>(out, n + 1);
    for (std::size_t i = 0; i < kHostStructs.size(); ++i)
        EXPECT_EQ(dev[i], kHostStructs[i].second) << "sizeof(" << kHostStructs[i].first << ")";
    for (std::size_t i = 0; i < kHostFields.size(); ++i) {
        const Field& f = kHostFields[i].second;
        const std::size_t at = kHostStructs.size() + 2 * i;
        EXPECT_EQ(dev[at], f.offset) << "offsetof " << f.name;
        EXPECT_EQ(dev[at + 1], f.size) << "sizeof " << f.name;
    }
    EXPECT_EQ(dev[n], 0xdeadbeefu);
}

// A field left out of shared_struct_fields.h would escape the comparison
// above: every struct's listed fields must cover it exactly, in order, with
// no gap and no overlap.
TEST(SharedStructs, TheFieldListCoversEveryStruct) {
    std::map<std::string, std::vector<Field>> by_struct;
    for (const auto& [s, f] : kHostFields) by_struct[s].push_back(f);
    for (const auto& [s, size] : kHostStructs) {
        auto fields = by_struct[s];
        ASSERT_FALSE(fields.empty()) << s;
        std::sort(fields.begin(), fields.end(), [](const Field& a, const Field& b) { return a.offset < b.offset; });
        std::uint32_t end = 0;
        for (const Field& f : fields) {
            EXPECT_EQ(f.offset, end) << s << ": a gap or overlap before " << f.name;
            end = f.offset + f.size;
        }
        EXPECT_EQ(end, size) << s << ": fields end before the struct does";
    }
    EXPECT_EQ(by_struct.size(), kHostStructs.size()) << "a field of a struct not in CLP_SHARED_STRUCTS";
}
