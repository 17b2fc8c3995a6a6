// tinybvh's OpenCL traversal kernels over the ray batches `clpath bench rays
// --save-rays DIR` wrote, on the same OpenCL device, checked against clpath's
// own hits. Our code; tinybvh (tiny_bvh.h and its .cl files) comes from the
// folder given as --tinybvh, a checkout the user fetched (see README.md).
//
// Why not tiny_ocl.h: its device search (Kernel::InitCL) accepts only devices
// with cl_khr_gl_sharing, which PoCL does not offer ("No capable OpenCL device
// found."), so the host side here is plain OpenCL; the program is built with
// the options tiny_ocl's Kernel uses and the vendor define it would add.
#define TINYBVH_IMPLEMENTATION
#include "tiny_bvh.h"

#include "clpath_kernels.hpp"
#include "obj_triangles.hpp"

#include <algorithm>
#include <chrono>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace harness;
using tinybvh::bvhvec3;
using tinybvh::bvhvec4;

// Our kernels beside tinybvh's own batch kernels: tinybvh's traverse.cl has
// occlusion functions for each layout but no batch kernel that calls them.
// Each ray's tmax rides in its hit.x (tinybvh's ray layout: O, D, rD, hit).
const char* kWrapperSource = R"CL(
#include "traverse.cl"
kernel void clp_occluded_ailalaine(const global struct BVHNode* bvhNode, const global uint* idx,
                                   const global float4* verts, const global struct Ray* rayData, global uint* occluded) {
    const uint i = get_global_id(0);
    occluded[i] = isoccluded_ailalaine(bvhNode, idx, verts, 0, rayData[i].O.xyz, rayData[i].D.xyz, rayData[i].rD.xyz,
                                       rayData[i].hit.x);
}
kernel void clp_occluded_gpu4way(const global float4* alt4Node, const global struct Ray* rayData, global uint* occluded) {
    const uint i = get_global_id(0);
    occluded[i] = isoccluded_gpu4way(alt4Node, rayData[i].O.xyz, rayData[i].D.xyz, rayData[i].rD.xyz, rayData[i].hit.x);
}
kernel void clp_occluded_cwbvh(global const float4* cwbvhNodes, global const float4* cwbvhTris,
                               const global struct Ray* rayData, global uint* occluded) {
    const uint i = get_global_id(0);
#ifdef SIMD_AABBTEST /* the operands as tinybvh's batch_cwbvh passes them */
    float4 O4 = rayData[i].O; O4.w = 1;
    float4 D4 = rayData[i].D; D4.w = 0;
    float4 rD4 = rayData[i].rD; rD4.w = 1;
    occluded[i] = isoccluded_cwbvh(cwbvhNodes, cwbvhTris, O4, D4, rD4, rayData[i].hit.x);
#else
    occluded[i] = isoccluded_cwbvh(cwbvhNodes, cwbvhTris, rayData[i].O.xyz, rayData[i].D.xyz, rayData[i].rD.xyz,
                                   rayData[i].hit.x);
#endif
}
)CL";

// tiny_ocl's Kernel builds with these options and puts a vendor define
// (ISNVIDIA, ISAMD, ISINTEL, ISAPPLE, else ISOTHER) before the source, chosen
// from the lower-cased device name; traverse.cl picks its variants by it.
// Those are GPU families (tiny_ocl accepts GPUs only): a CPU device gets
// ISOTHER, whatever its name says. PoCL names an AMD EPYC "...-AMD EPYC", and
// ISAMD's variant of traverse_cwbvh.cl does not compile there; ISINTEL,
// which a Xeon's name gave before, selects the same options as ISOTHER.
std::string vendor_define(cl_device_id device, std::string name) {
    cl_device_type type = 0;
    clGetDeviceInfo(device, CL_DEVICE_TYPE, sizeof type, &type, nullptr);
    if (type & CL_DEVICE_TYPE_CPU) return "ISOTHER";
    for (char& c : name) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (name.find("nvidia") != std::string::npos) return "ISNVIDIA";
    if (name.find("amd") != std::string::npos) return "ISAMD";
    if (name.find("intel") != std::string::npos) return "ISINTEL";
    if (name.find("apple") != std::string::npos) return "ISAPPLE";
    return "ISOTHER";
}

void build_program(Cl& cl, const std::string& tinybvh_dir, std::string& options) {
    options = "-I " + tinybvh_dir + " -D" + vendor_define(cl.device, cl.name) +
              " -cl-std=CL2.0 -cl-strict-aliasing -cl-fast-relaxed-math -cl-single-precision-constant";
    cl_int e;
    const char* src = kWrapperSource;
    cl.program = clCreateProgramWithSource(cl.context, 1, &src, nullptr, &e);
    check(e, "clCreateProgramWithSource");
    if (clBuildProgram(cl.program, 1, &cl.device, options.c_str(), nullptr, nullptr) != CL_SUCCESS) {
        std::size_t n = 0;
        clGetProgramBuildInfo(cl.program, cl.device, CL_PROGRAM_BUILD_LOG, 0, nullptr, &n);
        std::string log(n, '\0');
        clGetProgramBuildInfo(cl.program, cl.device, CL_PROGRAM_BUILD_LOG, n, log.data(), nullptr);
        throw Fail("building tinybvh's traverse.cl from " + tinybvh_dir + " failed:\n" + log);
    }
}


// ---- one layout's kernels over one batch ---------------------------------

struct Options {
    std::string obj, rays, tinybvh, csv, device, label = "scene";
    std::vector<std::string> layouts = {"ailalaine", "gpu4way", "cwbvh"};
    std::vector<std::string> batches = {"primary", "shadow", "diffuse"};
    int launches = 5;
    std::size_t workgroup = 64, triangles = 0;
    double tolerance = 1e-3;
    std::vector<std::string> builds = {"hq", "fast"};  // tinybvh's BuildHQ and Build trees, each timed
    bool paired = false;
};

struct Timing {
    std::vector<double> ms;
    double mean = 0, median = 0, best = 0;
};

Timing summarise(std::vector<double> ms) {
    Timing t;
    t.ms = ms;
    std::sort(ms.begin(), ms.end());
    t.best = ms.front();
    t.median = ms.size() % 2 ? ms[ms.size() / 2] : 0.5 * (ms[ms.size() / 2 - 1] + ms[ms.size() / 2]);
    for (double x : ms) t.mean += x / double(ms.size());
    return t;
}

// tinybvh's batch kernels have no bounds check, so the harness pads the ray
// buffers to the global size (launch_ms rounds n up to the work-group).
Timing time_kernel(const Cl& cl, cl_kernel k, std::size_t n, std::size_t wg, int launches) {
    std::vector<double> ms;
    for (int l = 0; l <= launches; ++l) {  // the first launch warms up and is not counted
        const double t = launch_ms(cl, k, n, wg);
        if (l > 0) ms.push_back(t);
    }
    return summarise(ms);
}

// --paired: tinybvh's kernel and clpath's, launched turn about (which goes
// first alternates), each warmed up once. ratio[l] is clpath's speed over
// tinybvh's in launch l: tinybvh's time over clpath's.
struct Paired {
    Timing tinybvh, clpath;
    std::vector<double> ratio;
};

Paired time_paired(const Cl& cl, cl_kernel k, ClpathBatch& c, std::size_t n, std::size_t wg, int launches) {
    launch_ms(cl, k, n, wg);
    c.launch();
    std::vector<double> tb, cp;
    Paired p;
    for (int l = 0; l < launches; ++l) {
        double a, b;
        if (l % 2 == 0) {
            a = launch_ms(cl, k, n, wg);
            b = c.launch();
        } else {
            b = c.launch();
            a = launch_ms(cl, k, n, wg);
        }
        tb.push_back(a), cp.push_back(b), p.ratio.push_back(a / b);
    }
    p.tinybvh = summarise(tb);
    p.clpath = summarise(cp);
    std::sort(p.ratio.begin(), p.ratio.end());
    return p;
}

double quantile(const std::vector<double>& sorted, double q) {
    const double x = q * double(sorted.size() - 1);
    const std::size_t i = std::size_t(x);
    return i + 1 < sorted.size() ? sorted[i] + (x - double(i)) * (sorted[i + 1] - sorted[i]) : sorted[i];
}

// tinybvh's GPU ray: O, D (normalised, as tinybvh::Ray makes it), rD =
// tinybvh_rcp(D), hit.x = tmax in units of the normalised D (BVH_FAR for an
// unbounded ray: tinybvh's kernels are built with -cl-fast-relaxed-math,
// which assumes no infinities).
struct GpuRay {
    float O[4], D[4], rD[4], hit[4];
};
static_assert(sizeof(GpuRay) == 64, "tinybvh's struct Ray is 64 bytes");

std::vector<GpuRay> to_tinybvh(const RayBatch& b, std::size_t padded, std::vector<float>& length) {
    std::vector<GpuRay> g(padded, GpuRay{{0, 0, 0, 0}, {0, 0, 1, 0}, {1e30f, 1e30f, 1, 0}, {0, 0, 0, 0}});
    length.resize(b.rays.size());
    for (std::size_t i = 0; i < b.rays.size(); ++i) {
        const SavedRay& r = b.rays[i];
        const bvhvec3 d(r.d[0], r.d[1], r.d[2]);
        length[i] = tinybvh::tinybvh_length(d);
        const tinybvh::Ray ray(bvhvec3(r.o[0], r.o[1], r.o[2]), d);
        const float tmax = std::isinf(r.tmax) ? BVH_FAR : std::min(BVH_FAR, r.tmax * length[i]);
        g[i] = GpuRay{{ray.O.x, ray.O.y, ray.O.z, 0}, {ray.D.x, ray.D.y, ray.D.z, 0}, {ray.rD.x, ray.rD.y, ray.rD.z, 0},
                      {tmax, 0, 0, 0}};
    }
    return g;
}

struct Check {
    std::size_t hits = 0, mismatched = 0, t_differs = 0, only_clpath = 0, only_tinybvh = 0;
    // Of the mismatches: tinybvh's hit lies within 1e-4 (t + max |o|) of the origin, where clpath found
    // nothing or a farther hit: the surface the ray leaves (clpath's kNearOrigin; closest hit only).
    std::size_t near_origin = 0;
    double max_rel_dt = 0;  // over hits both found: |dt| / (t + max |o|), clpath's measure of float error
    std::string first;
};

// Closest hit: tinybvh's t (along the normalised D) against clpath's saved t
// (in units of the saved d).
Check check_closest(const RayBatch& b, const std::vector<GpuRay>& g, const std::vector<float>& len, double tol) {
    Check c;
    for (std::size_t i = 0; i < b.rays.size(); ++i) {
        const SavedRay& r = b.rays[i];
        const bool tb_hit = g[i].hit[0] < BVH_FAR, clp_hit = std::isfinite(r.result);
        c.hits += tb_hit;
        const double origin = std::max({std::fabs(r.o[0]), std::fabs(r.o[1]), std::fabs(r.o[2])}) / len[i];
        const double t_tb = double(g[i].hit[0]) / len[i], t_clp = r.result;
        if (tb_hit != clp_hit) {
            (clp_hit ? c.only_clpath : c.only_tinybvh)++;
        } else if (tb_hit) {
            const double rel = std::fabs(t_tb - t_clp) / (t_clp + origin);
            c.max_rel_dt = std::max(c.max_rel_dt, rel);
            if (rel <= tol) continue;
            ++c.t_differs;
        } else {
            continue;
        }
        if (tb_hit && (!clp_hit || t_tb < t_clp) && t_tb <= 1e-4 * (t_tb + origin)) ++c.near_origin;
        if (!c.mismatched++) {
            char buf[300];
            std::snprintf(buf, sizeof buf, "ray %zu: o = (%.9g, %.9g, %.9g), d = (%.9g, %.9g, %.9g): clpath t %.9g, tinybvh t %.9g",
                          i, r.o[0], r.o[1], r.o[2], r.d[0], r.d[1], r.d[2], double(r.result),
                          tb_hit ? double(g[i].hit[0]) / len[i] : INFINITY);
            c.first = buf;
        }
    }
    return c;
}

Check check_any(const RayBatch& b, const std::vector<std::uint32_t>& occluded) {
    Check c;
    for (std::size_t i = 0; i < b.rays.size(); ++i) {
        const bool tb = occluded[i] != 0, clp = b.rays[i].result != 0;
        c.hits += tb;
        if (tb == clp) continue;
        (clp ? c.only_clpath : c.only_tinybvh)++;
        if (!c.mismatched++) c.first = "ray " + std::to_string(i) + (clp ? ": clpath occluded, tinybvh not" : ": tinybvh occluded, clpath not");
    }
    return c;
}

struct Layout {
    std::string name, structure;  // "gpu4way", "BVH4_GPU"
    double build_ms = 0;
    std::vector<std::unique_ptr<Mem>> data;  // the structure's device buffers, in kernel argument order
    std::string closest, occluded;           // kernel names
};

void run(const Options& o) {
    Cl cl;
    open_device(cl, o.device);
    std::string options;
    build_program(cl, o.tinybvh, options);
    std::printf("device: %s (%s)\nprogram: %s/traverse.cl + our occlusion kernels, options: %s\n", cl.name.c_str(),
                device_info(cl.device, CL_DEVICE_VERSION).c_str(), o.tinybvh.c_str(), options.c_str());

    std::vector<bvhvec4> tris = read_obj_triangles(o.obj);
    const std::uint32_t n = std::uint32_t(tris.size() / 3);
    std::printf("triangles: %u from %s\n", n, o.obj.c_str());
    if (o.triangles && o.triangles != n)
        throw Fail(o.obj + ": " + std::to_string(n) + " triangles, but the rays' scene has " + std::to_string(o.triangles));
    std::unique_ptr<ClpathProgram> clpath;
    if (o.paired) {
        clpath = std::make_unique<ClpathProgram>(cl, o.rays);
        if (clpath->triangle_count() != n)
            throw Fail(o.rays + "/triangles.bin: " + std::to_string(clpath->triangle_count()) + " triangles, the OBJ " +
                       std::to_string(n));
        std::printf("paired with clpath's batch kernels from %s (options: %s)\n", o.rays.c_str(), clpath->options().c_str());
    }

    FILE* csv = nullptr;
    if (!o.csv.empty()) {
        csv = std::fopen(o.csv.c_str(), "w");
        if (!csv) throw Fail(o.csv + ": cannot write");
        std::fprintf(csv, "scene,device,triangles,tracer,layout,kernel,build,build_ms,batch,rays,hits,workgroup,launches,"
                          "mean_ms,median_ms,best_ms,mrays_per_s,mismatched,t_differs,only_clpath,only_tinybvh,near_origin,max_rel_dt,"
                          "paired_clpath_mean_ms,paired_clpath_mrays_per_s,paired_ratio,paired_ratio_q1,paired_ratio_q3,"
                          "paired_clpath_differs\n");
    }
    // The structures are built one at a time, so only one is held at once.
    // Each build's trees in turn (the summary counts the faster of the two per layout and batch).
    for (const std::string& build : o.builds)
    for (const std::string& name : o.layouts) {
        const bool hq = build == "hq";
        Layout L;
        L.name = name;
        auto t0 = std::chrono::steady_clock::now();
        std::unique_ptr<tinybvh::BVH_GPU> b2;
        std::unique_ptr<tinybvh::BVH4_GPU> b4;
        std::unique_ptr<tinybvh::BVH8_CWBVH> b8;
        if (name == "ailalaine") {
            b2 = std::make_unique<tinybvh::BVH_GPU>();
            hq ? b2->BuildHQ(tris.data(), n) : b2->Build(tris.data(), n);
            L.structure = "BVH_GPU";
            L.data.push_back(std::make_unique<Mem>(cl, b2->usedNodes * sizeof(tinybvh::BVH_GPU::BVHNode), b2->bvhNode));
            L.data.push_back(std::make_unique<Mem>(cl, b2->idxCount * sizeof(std::uint32_t), b2->bvh.primIdx));
            L.data.push_back(std::make_unique<Mem>(cl, tris.size() * sizeof(bvhvec4), tris.data()));
            L.closest = "batch_ailalaine", L.occluded = "clp_occluded_ailalaine";
        } else if (name == "gpu4way") {
            b4 = std::make_unique<tinybvh::BVH4_GPU>();
            hq ? b4->BuildHQ(tris.data(), n) : b4->Build(tris.data(), n);
            L.structure = "BVH4_GPU";
            L.data.push_back(std::make_unique<Mem>(cl, b4->usedBlocks * sizeof(bvhvec4), b4->bvh4Data));
            L.closest = "batch_gpu4way", L.occluded = "clp_occluded_gpu4way";
        } else if (name == "cwbvh") {
            b8 = std::make_unique<tinybvh::BVH8_CWBVH>();
            hq ? b8->BuildHQ(tris.data(), n) : b8->Build(tris.data(), n);
            L.structure = "BVH8_CWBVH";
            L.data.push_back(std::make_unique<Mem>(cl, b8->usedBlocks * sizeof(bvhvec4), b8->bvh8Data));
            L.data.push_back(std::make_unique<Mem>(cl, b8->idxCount * 3 * sizeof(bvhvec4), b8->bvh8Tris));
            L.closest = "batch_cwbvh", L.occluded = "clp_occluded_cwbvh";
        } else {
            throw Fail("unknown layout '" + name + "' (ailalaine, gpu4way, cwbvh)");
        }
        L.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        std::printf("%s (%s): %s in %.0f ms\n", L.structure.c_str(), name.c_str(), hq ? "BuildHQ" : "Build", L.build_ms);
        std::fflush(stdout);
        b2.reset(), b4.reset(), b8.reset();  // the device holds its copy

        for (const std::string& batch : o.batches) {
            const RayBatch b = read_rays(o.rays + "/" + batch + ".rays", batch);
            if (b.rays.empty()) continue;
            if (!b.any_hit)
                for (const SavedRay& r : b.rays)
                    if (!std::isinf(r.tmax))
                        throw Fail(batch + ": a closest-hit ray with a finite tmax; tinybvh's batch kernels trace to 1e30");
            const std::size_t padded = (b.rays.size() + o.workgroup - 1) / o.workgroup * o.workgroup;
            std::vector<float> len;
            std::vector<GpuRay> g = to_tinybvh(b, padded, len);
            Mem rays(cl, g.size() * sizeof(GpuRay), g.data());
            std::unique_ptr<Mem> occ;
            const std::string kname = b.any_hit ? L.occluded : L.closest;
            cl_int e;
            cl_kernel k = clCreateKernel(cl.program, kname.c_str(), &e);
            check(e, "clCreateKernel");
            cl_uint arg = 0;
            for (auto& m : L.data) check(clSetKernelArg(k, arg++, sizeof(cl_mem), &m->m), "clSetKernelArg");
            check(clSetKernelArg(k, arg++, sizeof(cl_mem), &rays.m), "clSetKernelArg");
            if (b.any_hit) {
                occ = std::make_unique<Mem>(cl, padded * sizeof(std::uint32_t), nullptr);
                check(clSetKernelArg(k, arg++, sizeof(cl_mem), &occ->m), "clSetKernelArg");
            }
            Timing t;
            Paired pr;
            std::size_t clpath_differs = 0;
            if (clpath) {
                ClpathBatch cb(cl, *clpath, b, o.workgroup);
                pr = time_paired(cl, k, cb, b.rays.size(), o.workgroup, o.launches);
                t = pr.tinybvh;
                clpath_differs = cb.differs_from_saved(b);
            } else {
                t = time_kernel(cl, k, b.rays.size(), o.workgroup, o.launches);
            }
            clReleaseKernel(k);
            Check c;
            if (b.any_hit) {
                std::vector<std::uint32_t> flags(padded);
                check(clEnqueueReadBuffer(cl.queue, occ->m, CL_TRUE, 0, padded * 4, flags.data(), 0, nullptr, nullptr), "read");
                c = check_any(b, flags);
            } else {
                check(clEnqueueReadBuffer(cl.queue, rays.m, CL_TRUE, 0, g.size() * sizeof(GpuRay), g.data(), 0, nullptr, nullptr),
                      "read");
                c = check_closest(b, g, len, o.tolerance);
            }
            const double mrays = double(b.rays.size()) / (t.mean * 1e-3) * 1e-6;
            std::printf("%s %s: %zu rays (%zu hit), kernel %s, %.3f ms mean / %.3f median / %.3f best of %d, %.3f Mrays/s; "
                        "against clpath: %zu mismatched (%zu t beyond %.0e relative, %zu hit by clpath only, %zu by "
                        "tinybvh only; %zu at the origin), max relative dt %.2g\n",
                        L.structure.c_str(), batch.c_str(), b.rays.size(), c.hits, kname.c_str(), t.mean, t.median, t.best,
                        o.launches, mrays, c.mismatched, c.t_differs, o.tolerance, c.only_clpath, c.only_tinybvh, c.near_origin, c.max_rel_dt);
            if (!c.first.empty()) std::printf("  first mismatch: %s\n", c.first.c_str());
            const double clpath_mrays = clpath ? double(b.rays.size()) / (pr.clpath.mean * 1e-3) * 1e-6 : 0;
            if (clpath)
                std::printf("  paired, launch by launch: clpath %.3f ms mean, %.3f Mrays/s; clpath/%s per launch: median %.3f "
                            "(quartiles %.3f-%.3f); clpath's answers: %zu differ from those it saved\n",
                            pr.clpath.mean, clpath_mrays, L.structure.c_str(), quantile(pr.ratio, 0.5),
                            quantile(pr.ratio, 0.25), quantile(pr.ratio, 0.75), clpath_differs);
            std::fflush(stdout);
            if (csv) {
                std::fprintf(csv, "%s,\"%s\",%u,tinybvh,%s,%s,%s,%.1f,%s,%zu,%zu,%zu,%d,%.4f,%.4f,%.4f,%.4f,%zu,%zu,%zu,%zu,%zu,%.3g",
                             o.label.c_str(), cl.name.c_str(), n, L.structure.c_str(), kname.c_str(),
                             hq ? "BuildHQ" : "Build", L.build_ms, batch.c_str(), b.rays.size(), c.hits, o.workgroup,
                             o.launches, t.mean, t.median, t.best, mrays, c.mismatched, c.t_differs, c.only_clpath,
                             c.only_tinybvh, c.near_origin, c.max_rel_dt);
                if (clpath)
                    std::fprintf(csv, ",%.4f,%.4f,%.4f,%.4f,%.4f,%zu\n", pr.clpath.mean, clpath_mrays, quantile(pr.ratio, 0.5),
                                 quantile(pr.ratio, 0.25), quantile(pr.ratio, 0.75), clpath_differs);
                else
                    std::fprintf(csv, ",,,,,,\n");
            }
        }
    }
    if (csv && std::fclose(csv) != 0) throw Fail(o.csv + ": cannot write");
}

const char* kUsage =
    "usage: tinybvh_rays --obj SCENE.obj --rays DIR --tinybvh TINYBVH_DIR [options]\n"
    "  --obj FILE        the scene's triangles (clpath export SCENE out/x.json writes out/x.obj)\n"
    "  --rays DIR        primary.rays, shadow.rays, diffuse.rays from clpath bench rays --save-rays DIR\n"
    "  --tinybvh DIR     a tinybvh checkout: its traverse.cl (and the files it includes)\n"
    "  --layouts LIST    comma-separated, of ailalaine (BVH_GPU), gpu4way (BVH4_GPU), cwbvh (BVH8_CWBVH);\n"
    "                    default ailalaine,gpu4way,cwbvh\n"
    "  --batches LIST    of primary, shadow, diffuse (default: all three)\n"
    "  --launches N      timed launches per batch after one warm-up (default 5)\n"
    "  --workgroup N     work-items per group (default 64, as clpath's and tinybvh's speed test)\n"
    "  --build LIST      of hq (tinybvh's BuildHQ: spatial splits, what its speed test uses) and fast (Build);\n"
    "                    default hq,fast: both trees, each timed on every batch\n"
    "  --tolerance X     largest |t difference| / (t + max |origin|) counted as the same hit (default 1e-3)\n"
    "  --triangles N     fail unless the OBJ holds N triangles (the count clpath printed)\n"
    "  --device TEXT     the first OpenCL device whose name holds TEXT (default: the first device)\n"
    "  --label NAME      the scene's name in the CSV\n"
    "  --csv FILE        write one row per layout and batch\n"
    "  --paired          also run clpath's own batch kernels from DIR (batch_kernels.cl, nodes.bin, triangles.bin,\n"
    "                    as --save-rays writes them) in this process, launch by launch turn about with tinybvh's,\n"
    "                    and report clpath's speed over tinybvh's per launch (median, quartiles)\n";

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
            if (a == "--paired") {
                o.paired = true;
                continue;
            }
            if (a == "-h" || a == "--help") {
                std::fputs(kUsage, stdout);
                return 0;
            }
            if (i + 1 >= argc) throw Fail(a + ": needs a value\n" + kUsage);
            const std::string v = argv[++i];
            if (a == "--obj") o.obj = v;
            else if (a == "--rays") o.rays = v;
            else if (a == "--tinybvh") o.tinybvh = v;
            else if (a == "--layouts") o.layouts = split(v);
            else if (a == "--batches") o.batches = split(v);
            else if (a == "--launches") o.launches = std::max(1, std::atoi(v.c_str()));
            else if (a == "--workgroup") o.workgroup = std::size_t(std::max(1, std::atoi(v.c_str())));
            else if (a == "--build") {
                o.builds = split(v);
                for (const auto& b : o.builds)
                    if (b != "hq" && b != "fast") throw Fail("--build: '" + b + "' is neither hq nor fast");
            }
            else if (a == "--tolerance") o.tolerance = std::atof(v.c_str());
            else if (a == "--triangles") o.triangles = std::size_t(std::atoll(v.c_str()));
            else if (a == "--device") o.device = v;
            else if (a == "--label") o.label = v;
            else if (a == "--csv") o.csv = v;
            else throw Fail("unknown option " + a + "\n" + kUsage);
        }
        if (o.obj.empty() || o.rays.empty() || o.tinybvh.empty()) throw Fail(std::string("missing --obj, --rays or --tinybvh\n") + kUsage);
        run(o);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tinybvh_rays: error: %s\n", e.what());
        return 1;
    }
}
