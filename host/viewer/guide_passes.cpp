#include "viewer/guide_passes.hpp"

#include <algorithm>

#include "shared_structs.h"

namespace clpath::viewer {
namespace {

std::unique_ptr<IntegratorProgram> view_program(Context& ctx, const Renderer& renderer, std::uint32_t integrator) {
    RenderSettings s = renderer.settings();
    s.integrator = integrator;
    s.kernel_shape = KernelShape::Auto;  // the views have only the megakernel shape
    return std::make_unique<IntegratorProgram>(ctx, renderer.device_scene().summary(), s);
}

}  // namespace

GuidePasses::GuidePasses(Context& ctx, const Renderer& renderer) : ctx_(ctx) {
    albedo_.program = view_program(ctx, renderer, CLP_INTEGRATOR_ALBEDO);
    normals_.program = view_program(ctx, renderer, CLP_INTEGRATOR_NORMALS);
    restart(renderer);
}

void GuidePasses::restart(const Renderer& renderer) {
    const Camera& cam = renderer.camera();
    for (Pass* p : {&albedo_, &normals_}) {
        if (p->film && p->film->width() == cam.width && p->film->height() == cam.height)
            p->film->clear();
        else
            p->film = std::make_unique<Film>(ctx_, cam.width, cam.height);
        p->program->reset_stats();
    }
    albedo_done_ = normals_done_ = 0;
    albedo_image_ = Image{};
    guides_.reset();
}

Image GuidePasses::finish(Pass& pass) {
    pass.film->resolve_on_device(pass.program->resolve_kernel(), 1.0f);
    return pass.film->read_image().linear;
}

std::uint32_t GuidePasses::advance(const Renderer& renderer, std::uint32_t n) {
    if (ready() || n == 0) return 0;
    // One pass after the other: the albedo view, then the normals view.
    const bool albedo = albedo_done_ < kGuideSamples;
    Pass& pass = albedo ? albedo_ : normals_;
    std::uint64_t& done = albedo ? albedo_done_ : normals_done_;
    const auto add = std::uint32_t(std::min<std::uint64_t>(n, kGuideSamples - done));
    pass.program->add_samples(renderer.device_scene(), *pass.film, renderer.camera(), add);
    done += add;
    if (done < kGuideSamples) return add;
    if (albedo) {
        albedo_image_ = finish(albedo_);
    } else {
        auto g = std::make_shared<DenoiseGuides>();
        g->albedo = std::move(albedo_image_);
        g->normal = decode_normals_view(finish(normals_));
        g->clean = true;  // as render --denoise: kGuideSamples leave them noise-free enough for cleanAux
        guides_ = std::move(g);
    }
    return add;
}

}  // namespace clpath::viewer
