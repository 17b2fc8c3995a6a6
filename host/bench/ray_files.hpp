#pragma once
// Ray-batch files (clpath bench rays --save-rays DIR): each batch's rays and
// clpath's answers, so another tracer can trace the very same rays and be
// checked against them (benchmarks/rays/tinybvh/ does so for tinybvh).
//
// DIR/primary.rays, DIR/shadow.rays, DIR/diffuse.rays, each little-endian:
//   header, 32 bytes:
//     0  char[8]  "CLPRAYS1" (format version 1)
//     8  uint32   batch: 0 primary, 1 shadow, 2 diffuse
//    12  uint32   query: 0 closest hit, 1 any hit (shadow rays)
//    16  uint64   ray count N
//    24  uint32   record size, 32
//    28  uint32   0
//   then N records of 32 bytes, in the order clpath traced them:
//     float32 o[3]    origin
//     float32 tmax    hits count only at t < tmax, t in units of |d| (infinity: unbounded)
//     float32 d[3]    direction (not normalised for shadow rays: tmax 1 is the light)
//     float32 result  closest hit: clpath's hit distance t (units of |d|), +infinity for a miss;
//                     any hit: 1 if clpath found an occluder before tmax, else 0
//
// Beside them, what clpath's batch kernels were given besides the rays, so a
// harness can run those very kernels in its own process, launch by launch
// beside another tracer's (benchmarks/rays/tinybvh/ does, with --paired):
//   DIR/batch_kernels.cl       the program's source as clpath builds it (its includes in place)
//   DIR/batch_kernels.options  its build options, one line
//   DIR/nodes.bin              the acceleration nodes, byte for byte as on the device
//   DIR/triangles.bin          the triangles (48-byte TriVerts, shared_structs.h), likewise
// The kernels: batch_trace_closest(nodes, triangles, rays, hits, uint count),
// writing a 16-byte Hit (float t, b1, b2; int tri, -1 for a miss) per ray,
// and batch_trace_any(nodes, triangles, rays, occluder, uint count), writing
// an int per ray (-1: none). They read a ray file's records as they are: a
// record is a BatchRay, whose last field (src) they do not read.
#include <cstdint>
#include <string>
#include <vector>

#include "shared_structs.h"

namespace clpath {

enum class RayBatchKind : std::uint32_t { Primary = 0, Shadow = 1, Diffuse = 2 };

// The batch's file name in DIR: "primary.rays", ...
std::string ray_file_name(RayBatchKind kind);

// Throws clpath::Error naming the option unless dir is an existing, writable folder.
void check_ray_folder(const std::string& dir, const std::string& what);

// The file's bytes (header and records); result holds one answer per ray (see above).
std::string encode_ray_file(RayBatchKind kind, const std::vector<BatchRay>& rays, const std::vector<float>& result);

// The file names of the kernels' inputs above, in DIR.
constexpr const char* kBatchKernelsFile = "batch_kernels.cl";
constexpr const char* kBatchOptionsFile = "batch_kernels.options";
constexpr const char* kNodesFile = "nodes.bin";
constexpr const char* kTrianglesFile = "triangles.bin";

// The answers to store: hit t or +infinity (closest hit), 1 or 0 (any hit: occluder index or -1).
std::vector<float> closest_hit_results(const std::vector<Hit>& hits);
std::vector<float> any_hit_results(const std::vector<int>& occluder);

}  // namespace clpath
