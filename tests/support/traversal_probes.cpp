#include "support/traversal_probes.hpp"

#include "support/test_device.hpp"

namespace clpath::test {

Traced trace_bvh(const Bvh& bvh, const std::vector<float>& rays, const std::vector<float>& tmax) {
    const std::uint32_t n = std::uint32_t(tmax.size());
    Kernel k = device().kernel(probe_program(), "probe_trace");
    Buffer nodes = upload(device_nodes(Accel::Bvh, bvh, node_layout())), tris = upload(bvh.triangles), rb = upload(rays), tb = upload(tmax);
    Buffer ot = device().buffer(n * sizeof(float), CL_MEM_READ_WRITE, "t");
    Buffer op = device().buffer(n * sizeof(int), CL_MEM_READ_WRITE, "prim");
    Buffer oa = device().buffer(n * sizeof(int), CL_MEM_READ_WRITE, "any");
    k.arg(0, nodes).arg(1, tris).arg(2, rb).arg(3, tb).arg(4, ot).arg(5, op).arg(6, oa).arg(7, n);
    run(k, n);
    return {download<float>(ot, n), download<int>(op, n), download<int>(oa, n)};
}

Traced trace_brute(const BvhTriangles& tris, const std::vector<float>& rays) {
    const std::uint32_t n = std::uint32_t(rays.size() / 6), tc = std::uint32_t(tris.size());
    Kernel k = device().kernel(probe_program(), "probe_brute");
    Buffer tb = upload(tris), rb = upload(rays);
    Buffer ot = device().buffer(n * sizeof(float), CL_MEM_READ_WRITE, "t");
    Buffer op = device().buffer(n * sizeof(int), CL_MEM_READ_WRITE, "prim");
    k.arg(0, tb).arg(1, tc).arg(2, rb).arg(3, ot).arg(4, op).arg(5, n);
    run(k, n);
    return {download<float>(ot, n), download<int>(op, n), {}};
}

BvhTriangles device_triangles(const std::vector<glm::vec3>& verts) {
    const std::uint32_t tc = std::uint32_t(verts.size() / 3);
    BvhTriangles tris(tc, TriVerts{});
    for (std::uint32_t i = 0; i < tc; ++i) {
        for (int c = 0; c < 3; ++c) {
            tris[i].v0[c] = verts[3 * i][c];
            tris[i].v1[c] = verts[3 * i + 1][c];
            tris[i].v2[c] = verts[3 * i + 2][c];
        }
        tris[i].prim = i;
    }
    return tris;
}

}  // namespace clpath::test
