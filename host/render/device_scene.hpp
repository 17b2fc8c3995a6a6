#pragma once
// A prepared scene's arrays on one device: geometry, acceleration structure,
// materials, lights and environment, uploaded once and read by every launch.
// Several DeviceScenes (one per Context) can be made from one PreparedScene.
#include <array>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "cl/context.hpp"
#include "render/prepared_scene.hpp"

namespace clpath {

// The scene's buffers, named and ordered by the one table the kernels'
// parameter lists come from (CLP_SCENE_BUFFERS, kernels/shared_structs.h).
enum class SceneBuffer : cl_uint {
#define CLP_SCENE_BUFFER_NAME(type, name) name,
    CLP_SCENE_BUFFERS(CLP_SCENE_BUFFER_NAME)
#undef CLP_SCENE_BUFFER_NAME
        count
};
// The buffers' parameter names, in order (for checking a kernel's arguments).
const std::vector<std::string>& scene_buffer_names();

class DeviceScene {
public:
    // Checks that the arrays fit on the device, then uploads them, the nodes
    // as given in the device's layout (scene_node_bytes(scene,
    // device_node_layout(...))): the caller widens the tree once, for its own
    // sizing too (at 10^7 triangles a widening takes about half a second and
    // 0.4 GB). Throws clpath::Error naming the part that does not fit.
    DeviceScene(Context& ctx, const PreparedScene& scene, const std::vector<unsigned char>& node_bytes);

    // The buffers this scene needs on a device, by name (for Context::check_fits),
    // its nodes in that device's layout (device_node_layout), node_bytes of them.
    static std::vector<std::pair<std::string, std::size_t>> memory_needs(const PreparedScene& scene,
                                                                         std::size_t node_bytes);
    // As above, sizing the nodes by converting them.
    static std::vector<std::pair<std::string, std::size_t>> memory_needs(const PreparedScene& scene, NodeLayout layout);
    // The node layout a device's programs walk for this scene (render/kernel_programs.hpp, node_layout).
    static NodeLayout device_node_layout(const DeviceInfo& device, const PreparedScene& scene);

    // Number of kernel arguments bind() sets.
    static constexpr cl_uint kArgCount = cl_uint(SceneBuffer::count);
    // Sets the buffers as arguments first ... first + kArgCount - 1, in the
    // table's order (a kernel declares them with CLP_SCENE_PARAMS).
    void bind(Kernel& kernel, cl_uint first = 0) const;

    const SceneSummary& summary() const { return summary_; }
    Context& context() const { return ctx_; }
    // The BVH nodes' buffer (so a caller can tell that it was not uploaded again).
    const Buffer& nodes() const { return buffer(SceneBuffer::nodes); }
    const Buffer& buffer(SceneBuffer b) const { return buffers_[std::size_t(b)]; }
    // The bytes of all its buffers.
    std::size_t bytes() const;

private:
    Buffer& slot(SceneBuffer b) { return buffers_[std::size_t(b)]; }

    Context& ctx_;
    SceneSummary summary_;
    std::array<Buffer, kArgCount> buffers_;
};

}  // namespace clpath
