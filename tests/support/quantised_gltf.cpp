#include "support/quantised_gltf.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace clpath::test {

QuantisedGltf quantise_like_gltfpack(const GltfPrimitive& p, const std::vector<std::string>& image_uris,
                                     const std::string& bin_uri) {
    using nlohmann::json;
    QuantisedGltf q;
    const std::size_t n = p.vertices.size();
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    glm::vec2 uv_lo(INFINITY), uv_hi(-INFINITY);
    for (std::size_t i = 0; i < n; ++i) {
        lo = glm::min(lo, p.vertices[i]);
        hi = glm::max(hi, p.vertices[i]);
        uv_lo = glm::min(uv_lo, p.uvs[i]);
        uv_hi = glm::max(uv_hi, p.uvs[i]);
    }
    q.lo = lo;
    q.extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    q.step = q.extent / 65535.0f;  // one grid for all axes, as gltfpack keeps the aspect
    q.uv_lo = uv_lo;
    q.uv_scale = uv_hi - uv_lo;
    std::string pos_bin, nrm_bin, uv_bin;
    for (std::size_t i = 0; i < n; ++i) {
        std::uint16_t qp[3];
        for (int c = 0; c < 3; ++c) qp[c] = std::uint16_t(std::lround((p.vertices[i][c] - lo[c]) / q.step));
        pos_bin.append(reinterpret_cast<const char*>(qp), 6);
        pos_bin.append(2, '\0');  // gltfpack pads each position to 4-byte alignment
        std::int8_t qn[4] = {0, 0, 0, 0};
        const glm::vec3 nn = glm::normalize(p.normals[i]);
        for (int c = 0; c < 3; ++c) qn[c] = std::int8_t(std::lround(nn[c] * 127.0f));
        nrm_bin.append(reinterpret_cast<const char*>(qn), 4);
        std::uint16_t qt[2];
        for (int c = 0; c < 2; ++c)
            qt[c] = std::uint16_t(std::lround((p.uvs[i][c] - uv_lo[c]) / q.uv_scale[c] * 65535.0f));
        uv_bin.append(reinterpret_cast<const char*>(qt), 4);
    }
    q.bin = pos_bin + nrm_bin + uv_bin;
    const json transform = {{"KHR_texture_transform",
                             {{"offset", {uv_lo.x, uv_lo.y}}, {"scale", {q.uv_scale.x, q.uv_scale.y}}}}};
    json pbr = json::object();
    json images = json::array(), textures = json::array();
    const char* slots[2] = {"baseColorTexture", "metallicRoughnessTexture"};
    for (std::size_t i = 0; i < image_uris.size() && i < 2; ++i) {
        images.push_back({{"uri", image_uris[i]}});
        textures.push_back({{"source", i}});
        pbr[slots[i]] = {{"index", i}, {"extensions", transform}};
    }
    q.doc = {
        {"asset", {{"version", "2.0"}, {"generator", "a gltfpack-like quantiser (clpath test)"}}},
        {"extensionsUsed", {"KHR_mesh_quantization", "KHR_texture_transform"}},
        {"extensionsRequired", {"KHR_mesh_quantization"}},
        {"buffers", {{{"byteLength", q.bin.size()}, {"uri", bin_uri}}}},
        {"bufferViews",
         {{{"buffer", 0}, {"byteLength", pos_bin.size()}, {"byteStride", 8}},
          {{"buffer", 0}, {"byteOffset", pos_bin.size()}, {"byteLength", nrm_bin.size()}, {"byteStride", 4}},
          {{"buffer", 0},
           {"byteOffset", pos_bin.size() + nrm_bin.size()},
           {"byteLength", uv_bin.size()},
           {"byteStride", 4}}}},
        {"accessors",
         {{{"bufferView", 0}, {"componentType", 5123}, {"count", n}, {"type", "VEC3"}},
          {{"bufferView", 1}, {"componentType", 5120}, {"normalized", true}, {"count", n}, {"type", "VEC3"}},
          {{"bufferView", 2}, {"componentType", 5123}, {"normalized", true}, {"count", n}, {"type", "VEC2"}}}},
        {"materials", {{{"pbrMetallicRoughness", pbr}}}},
        {"meshes",
         {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}}, {"material", 0}}}}}}},
        {"nodes", {{{"mesh", 0}, {"translation", {lo.x, lo.y, lo.z}}, {"scale", {q.step, q.step, q.step}}}}},
        {"scenes", {{{"nodes", {0}}}}},
        {"scene", 0}};
    if (!images.empty()) {
        q.doc["images"] = images;
        q.doc["textures"] = textures;
    }
    return q;
}

}  // namespace clpath::test
