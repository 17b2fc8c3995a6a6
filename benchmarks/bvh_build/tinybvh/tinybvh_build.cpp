// tinybvh's BVH builders timed on the triangles of a clpath scene (the OBJ
// `clpath export` writes), beside `clpath bench build` (benchmarks/bvh_build/run.sh).
// Our code; tinybvh (tiny_bvh.h) comes from the checkout named by build.sh's
// TINYBVH_DIR, compiled as tinybvh's own CMake file compiles it (-O3
// -march=native), so that on an AVX machine BuildDefault is BuildAVX, as
// tinybvh ships it.
#define TINYBVH_IMPLEMENTATION
#include "tiny_bvh.h"

#include "../../rays/tinybvh/obj_triangles.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace {

using tinybvh::bvhvec4;

struct Options {
    std::string obj, csv, label = "scene";
    std::vector<std::string> builders = {"default", "build"};
    int repeat = 3;
};

struct TreeFacts {
    double sah = 0;  // over the root's area: 1 per interior node, 1 per triangle in a leaf (clpath's measure)
    std::uint32_t nodes = 0, leaves = 0, max_leaf = 0, depth = 0;
};

// clpath's SAH measure (host/bvh/binned_builder.cpp): each interior node's area, each
// leaf's area times its triangles, over the root's area. tinybvh's SAHCost
// with c_trav = c_int = 1 is the same sum; walked here so that the facts beside it come from one pass.
TreeFacts facts(const tinybvh::BVH& bvh) {
    TreeFacts f;
    const double root = bvh.bvhNode[0].SurfaceArea();
    struct Item {
        std::uint32_t node, depth;
    };
    std::vector<Item> stack{{0, 1}};
    while (!stack.empty()) {
        const Item it = stack.back();
        stack.pop_back();
        const tinybvh::BVH::BVHNode& n = bvh.bvhNode[it.node];
        ++f.nodes;
        f.depth = std::max(f.depth, it.depth);
        if (n.isLeaf()) {
            ++f.leaves;
            f.max_leaf = std::max(f.max_leaf, n.triCount);
            f.sah += double(n.triCount) * n.SurfaceArea() / root;
        } else {
            f.sah += n.SurfaceArea() / root;
            stack.push_back({n.leftFirst, it.depth + 1});
            stack.push_back({n.leftFirst + 1, it.depth + 1});
        }
    }
    return f;
}

double cpu_ms() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return double(ts.tv_sec) * 1e3 + double(ts.tv_nsec) * 1e-6;
}

// BVH::BuildDefault is protected: tinybvh's layouts (BVH_GPU, BVH4_GPU,
// BVH8_CPU, ...) build their BVH with it. Made callable here, unchanged.
struct BVHWithDefault : tinybvh::BVH {
    using tinybvh::BVH::BuildDefault;
};

// "default": BuildDefault (BuildAVX where AVX is compiled in: what tinybvh
// builds its layouts with), "avx": BuildAVX, "build": Build (the reference
// binned builder), "hq": BuildHQ (spatial splits).
std::function<void(tinybvh::BVH&, const bvhvec4*, std::uint32_t)> builder(const std::string& name) {
    if (name == "default")
        return [](tinybvh::BVH& b, const bvhvec4* v, std::uint32_t n) { static_cast<BVHWithDefault&>(b).BuildDefault(v, n); };
    if (name == "avx") return [](tinybvh::BVH& b, const bvhvec4* v, std::uint32_t n) { b.BuildAVX(v, n); };
    if (name == "build") return [](tinybvh::BVH& b, const bvhvec4* v, std::uint32_t n) { b.Build(v, n); };
    if (name == "hq") return [](tinybvh::BVH& b, const bvhvec4* v, std::uint32_t n) { b.BuildHQ(v, n); };
    throw std::runtime_error("unknown builder '" + name + "' (default, avx, build, hq)");
}

std::string builder_label(const std::string& name) {
#if defined BVH_USEAVX
    if (name == "default") return "BuildDefault (BuildAVX)";
#elif defined BVH_USENEON
    if (name == "default") return "BuildDefault (BuildNEON)";
#else
    if (name == "default") return "BuildDefault (Build)";
#endif
    return name == "avx" ? "BuildAVX" : name == "build" ? "Build" : "BuildHQ";
}

int run(const Options& o) {
    const std::vector<bvhvec4> tris = harness::read_obj_triangles(o.obj);
    const std::uint32_t n = std::uint32_t(tris.size() / 3);
#if defined BVH_USEAVX
    const char* simd = "AVX compiled in";
#else
    const char* simd = "no AVX compiled in";
#endif
    std::printf("tinybvh %d.%d.%d (%s), %u triangles from %s, %d builds each\n", TINY_BVH_VERSION_MAJOR,
                TINY_BVH_VERSION_MINOR, TINY_BVH_VERSION_SUB, simd, n, o.obj.c_str(), o.repeat);
    FILE* csv = nullptr;
    if (!o.csv.empty()) {
        csv = std::fopen(o.csv.c_str(), "w");
        if (!csv) throw std::runtime_error(o.csv + ": cannot write");
        std::fprintf(csv, "scene,triangles,builder,runs,median_ms,min_ms,max_ms,mtris_per_s,sah_cost,nodes,leaves,max_leaf,depth\n");
    }
    for (const std::string& name : o.builders) {
        const auto build = builder(name);
        std::vector<double> ms;
        TreeFacts f;
        for (int r = 0; r < o.repeat; ++r) {
            // A new BVH each time, as a program building its scene once has: the build's allocations are timed too
            // (as clpath's bench build times its own).
            auto bvh = std::make_unique<BVHWithDefault>();
            const double c0 = cpu_ms();
            const auto t0 = std::chrono::steady_clock::now();
            build(*bvh, tris.data(), n);
            const double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
            const double cpu = cpu_ms() - c0;
            ms.push_back(wall);
            f = facts(*bvh);
            std::printf("%s run %d: %.2f ms, CPU time %.2f ms\n", builder_label(name).c_str(), r + 1, wall, cpu);
        }
        std::vector<double> sorted = ms;
        std::sort(sorted.begin(), sorted.end());
        const double median = sorted[sorted.size() / 2];
        const double mtris = double(n) / (median * 1e-3) * 1e-6;
        std::printf("tinybvh %s: %u triangles, median %.2f ms of %d, %.2f Mtris/s, SAH %.2f, %u nodes, %u leaves (at most %u "
                    "triangles), depth %u\n",
                    builder_label(name).c_str(), n, median, o.repeat, mtris, f.sah, f.nodes, f.leaves, f.max_leaf, f.depth);
        std::fflush(stdout);
        if (csv)
            std::fprintf(csv, "%s,%u,\"%s\",%d,%.3f,%.3f,%.3f,%.3f,%.4f,%u,%u,%u,%u\n", o.label.c_str(), n,
                         builder_label(name).c_str(), o.repeat, median, sorted.front(), sorted.back(), mtris, f.sah,
                         f.nodes, f.leaves, f.max_leaf, f.depth);
    }
    if (csv && std::fclose(csv) != 0) throw std::runtime_error(o.csv + ": cannot write");
    return 0;
}

const char* kUsage =
    "usage: tinybvh_build --obj SCENE.obj [options]\n"
    "  --obj FILE        the scene's triangles (clpath export SCENE out/x.json writes out/x.obj)\n"
    "  --builders LIST   comma-separated, of default (BuildDefault), avx (BuildAVX), build (Build), hq (BuildHQ);\n"
    "                    default: default,build\n"
    "  --repeat N        builds per builder, the median reported (default 3)\n"
    "  --label NAME      the scene's name in the CSV\n"
    "  --csv FILE        write one row per builder\n";

std::vector<std::string> split(const std::string& s) {
    std::vector<std::string> v;
    std::stringstream ss(s);
    for (std::string x; std::getline(ss, x, ',');)
        if (!x.empty()) v.push_back(x);
    return v;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        Options o;
        for (int i = 1; i < argc; ++i) {
            const std::string a = argv[i];
            if (a == "-h" || a == "--help") {
                std::fputs(kUsage, stdout);
                return 0;
            }
            if (i + 1 >= argc) throw std::runtime_error(a + ": needs a value\n" + kUsage);
            const std::string v = argv[++i];
            if (a == "--obj") o.obj = v;
            else if (a == "--builders") o.builders = split(v);
            else if (a == "--repeat") o.repeat = std::max(1, std::atoi(v.c_str()));
            else if (a == "--label") o.label = v;
            else if (a == "--csv") o.csv = v;
            else throw std::runtime_error("unknown option " + a + "\n" + kUsage);
        }
        if (o.obj.empty()) throw std::runtime_error(std::string("missing --obj\n") + kUsage);
        for (const auto& b : o.builders) builder(b);  // refuses an unknown name before any work
        return run(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tinybvh_build: error: %s\n", e.what());
        return 1;
    }
}
