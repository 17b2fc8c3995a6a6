#pragma once
// The denoiser's guides, rendered as two extra passes after the estimate:
// the albedo and normals views (CLP_INTEGRATOR_ALBEDO, _NORMALS) of the same
// scene, camera and devices. The views take one ray per sample and see the
// same box-filtered pixel footprint as the estimate (the same jittered camera
// rays), so at kGuideSamples their only noise is sub-pixel coverage at edges
// and texture detail, small enough for OIDN's cleanAux. Separate passes leave
// the estimate's kernels and bits untouched.
#include <cstdint>
#include <vector>

#include "cl/device.hpp"
#include "denoise/denoiser.hpp"
#include "render/settings.hpp"
#include "scene/scene.hpp"

namespace clpath {

class ProcessGroup;

constexpr std::uint64_t kGuideSamples = 64;

struct GuideRender {
    DenoiseGuides guides;  // on the lead only
    double seconds = 0;    // both passes, scene preparation included
    bool leads = true;
};

// Every process of a group calls it (the passes render over the group like
// the estimate); the guides come back on the lead.
GuideRender render_guides(const Scene& scene, const RenderSettings& settings, const std::vector<DeviceInfo>& devices,
                          std::uint64_t spp = kGuideSamples, ProcessGroup* group = nullptr);

// The normals view's [0, 1] encoding (n/2 + 1/2; 0 where nothing is hit)
// back to [-1, 1]. Pixels where nothing is hit become (-1, -1, -1): one
// constant, noise-free value, which is all OIDN needs of the background.
Image decode_normals_view(const Image& view);

}  // namespace clpath
