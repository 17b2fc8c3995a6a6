#include "denoise/denoiser.hpp"

#include "denoise/oidn_library.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

// OIDN keeps the first error since the last query, per device and thread.
void check(const OidnApi& oidn, void* device, const char* what) {
    const char* message = nullptr;
    if (oidn.get_device_error(device, &message) != kOidnErrorNone)
        throw Error(std::string("Open Image Denoise: ") + what + ": " + (message ? message : "unknown error"));
}

void check_size(const Image& image, const Image& color, const char* name) {
    if (image.width != color.width || image.height != color.height ||
        image.rgb.size() != std::size_t(color.width) * color.height * 3)
        throw Error(std::string("denoising: the ") + name + " guide is " + std::to_string(image.width) + "x" +
                    std::to_string(image.height) + ", the image " + std::to_string(color.width) + "x" +
                    std::to_string(color.height));
}

}  // namespace

Denoiser::Denoiser() {
    const OidnApi& oidn = oidn_api();
    device_ = oidn.new_device(kOidnDeviceTypeCpu);
    // A failed device construction is reported on the null device.
    if (!device_) check(oidn, nullptr, "making the CPU device");
    oidn.commit_device(device_);
    check(oidn, device_, "starting the CPU device");
}

Denoiser::~Denoiser() {
    if (device_) oidn_api().release_device(device_);
}

const std::string& Denoiser::library_path() const { return oidn_api().path; }

Image Denoiser::denoise(const Image& color, const DenoiseGuides* guides) const {
    const OidnApi& oidn = oidn_api();
    check_size(color, color, "colour");
    if (guides) {
        check_size(guides->albedo, color, "albedo");
        check_size(guides->normal, color, "normal");
    }
    Image out;
    out.width = color.width;
    out.height = color.height;
    out.rgb.assign(color.rgb.size(), 0.0f);
    void* filter = oidn.new_filter(device_, "RT");
    check(oidn, device_, "making the RT filter");
    const auto share = [&](const char* name, const Image& image) {
        // OIDN reads the inputs only; its API takes a non-const pointer for all images.
        oidn.set_shared_filter_image(filter, name, const_cast<float*>(image.rgb.data()), kOidnFormatFloat3,
                                     std::size_t(image.width), std::size_t(image.height), 0, 0, 0);
    };
    share("color", color);
    share("output", out);
    if (guides) {
        share("albedo", guides->albedo);
        share("normal", guides->normal);
        oidn.set_filter_bool(filter, "cleanAux", guides->clean);
    }
    // Linear radiance, unbounded: the HDR model.
    oidn.set_filter_bool(filter, "hdr", true);
    oidn.commit_filter(filter);
    oidn.execute_filter(filter);
    const char* message = nullptr;
    const int error = oidn.get_device_error(device_, &message);
    const std::string text = message ? message : "unknown error";
    oidn.release_filter(filter);
    if (error != kOidnErrorNone) throw Error("Open Image Denoise: denoising failed: " + text);
    return out;
}

}  // namespace clpath
