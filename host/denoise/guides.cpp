#include "denoise/guides.hpp"

#include <chrono>

#include "render/render_session.hpp"
#include "shared_structs.h"

namespace clpath {

Image decode_normals_view(const Image& view) {
    Image n = view;
    for (float& v : n.rgb) v = 2.0f * v - 1.0f;
    return n;
}

GuideRender render_guides(const Scene& scene, const RenderSettings& settings, const std::vector<DeviceInfo>& devices,
                          std::uint64_t spp, ProcessGroup* group) {
    const auto start = std::chrono::steady_clock::now();
    const auto pass = [&](std::uint32_t integrator) {
        RenderSettings s = settings;
        s.integrator = integrator;
        // The views have only the megakernel shape.
        s.kernel_shape = KernelShape::Auto;
        SessionOptions so;
        so.spp = spp;
        return render_session(scene, s, devices, so, {}, group);
    };
    GuideRender r;
    SessionResult albedo = pass(CLP_INTEGRATOR_ALBEDO);
    SessionResult normals = pass(CLP_INTEGRATOR_NORMALS);
    r.leads = albedo.leads;
    if (r.leads) {
        r.guides.albedo = albedo.film.mean();
        r.guides.normal = decode_normals_view(normals.film.mean());
        r.guides.clean = true;
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return r;
}

}  // namespace clpath
