#pragma once
// A prepared scene's arrays on one device: geometry, acceleration structure,
// materials, lights and environment, uploaded once and read by every launch.
// Several DeviceScenes (one per Context) can be made from one PreparedScene.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "cl/context.hpp"
#include "render/prepared_scene.hpp"

namespace clpath {

class DeviceScene {
public:
    // Checks that the arrays fit on the device, then uploads them. Throws
    // clpath::Error naming the part that does not fit.
    DeviceScene(Context& ctx, const PreparedScene& scene);

    // The buffers this scene needs on a device, by name (for Context::check_fits).
    static std::vector<std::pair<std::string, std::size_t>> memory_needs(const PreparedScene& scene);

    // Number of kernel arguments bind() sets.
    static constexpr cl_uint kArgCount = 13;
    // Sets the arrays as arguments first ... first + kArgCount - 1, in the
    // order of render_paths' parameters (kernels/integrator.cl): nodes,
    // triangles, triangle materials, materials, material extensions, normals, lights, alias table,
    // environment image, environment distribution, surface attributes,
    // texture descriptors, texels.
    void bind(Kernel& kernel, cl_uint first = 0) const;

    const SceneSummary& summary() const { return summary_; }
    Context& context() const { return ctx_; }
    // The BVH nodes' buffer (so a caller can tell that it was not uploaded again).
    const Buffer& nodes() const { return nodes_; }

private:
    Context& ctx_;
    SceneSummary summary_;
    Buffer nodes_, tris_, tri_material_, materials_, material_ext_, normals_, lights_, alias_, env_pixels_, env_cdf_;
    Buffer attrs_, tex_desc_, texels_;
};

}  // namespace clpath
