#include "bvh/accel.hpp"

#include <cstring>

#include "bvh/flat.hpp"
#include "bvh/wide.hpp"
#include "util/error.hpp"

namespace clpath {

const std::vector<std::string>& accel_names() {
    static const std::vector<std::string> names{"bvh", "flat"};  // indexed by Accel
    return names;
}

Accel parse_accel(const std::string& name) {
    for (std::size_t i = 0; i < accel_names().size(); ++i)
        if (accel_names()[i] == name) return Accel(i);
    throw Error("unknown acceleration structure '" + name + "' (choose one of: bvh, flat)");
}

const char* accel_name(Accel accel) { return accel_names().at(std::size_t(accel)).c_str(); }

Bvh build_accel(Accel accel, const std::vector<glm::vec3>& vertices,
                const std::vector<std::uint32_t>& triangle_object, const BvhBuildOptions& options) {
    if (accel == Accel::Flat) return build_flat(vertices, triangle_object, options.traversal_cost);
    return build_bvh(vertices, options);
}

std::vector<unsigned char> device_nodes(Accel accel, const Bvh& structure, NodeLayout layout) {
    std::vector<unsigned char> bytes;
    auto copy = [&bytes](const auto& records) {
        bytes.resize(records.size() * sizeof(records[0]));
        std::memcpy(bytes.data(), records.data(), bytes.size());
    };
    if (accel == Accel::Flat)
        copy(structure.nodes);
    else if (layout == NodeLayout::Bvh8)
        copy(widen_bvh8(structure.nodes));
    else
        copy(widen_bvh(structure.nodes));
    return bytes;
}

}  // namespace clpath
