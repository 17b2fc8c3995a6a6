#pragma once
// Denoises a rendered image with Open Image Denoise's RT filter (a neural
// network trained on path-traced images), guided by first-hit albedo and
// normal images where given. The estimate itself is never changed: the
// denoised image is a new one.
#include "image/image.hpp"

namespace clpath {

// The auxiliary images of OIDN's RT filter ("Albedos", "Normals" of its API
// documentation): albedo in [0, 1], normals in [-1, 1] (any length), the
// same size as the colour. `clean` says they are noise-free (OIDN's
// cleanAux: sharper detail, but any noise left in them stays in the output).
struct DenoiseGuides {
    Image albedo, normal;
    bool clean = true;
};

class Denoiser {
public:
    // Loads the library (render --denoise fails here, before rendering, when
    // it is missing) and makes its CPU device: the images live in host memory,
    // which OIDN's shared images reach on the CPU device without copies.
    Denoiser();
    ~Denoiser();
    Denoiser(const Denoiser&) = delete;
    Denoiser& operator=(const Denoiser&) = delete;

    // The denoised colour (linear, HDR). guides may be null (colour alone).
    // Throws clpath::Error with OIDN's message if the filter fails.
    Image denoise(const Image& color, const DenoiseGuides* guides) const;

    // The library file in use, for messages.
    const std::string& library_path() const;

private:
    void* device_ = nullptr;
};

}  // namespace clpath
