#include "image/texture_io.hpp"

#include "util/error.hpp"

#ifdef CLPATH_WITH_OIIO
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#endif

namespace clpath {

TextureImage decode_texture(const std::string& bytes, const std::string& name) {
    const std::string fail = name + ": cannot decode the image: ";
    if (bytes.empty()) throw Error(fail + "it is empty");
#ifdef CLPATH_WITH_OIIO
    OIIO::Filesystem::IOMemReader mem(bytes.data(), bytes.size());
    OIIO::ImageSpec config;
    void* proxy = &mem;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    // glTF and MTL alpha is coverage, not premultiplied: keep colour as stored.
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(name, &config);
    if (!in) throw Error(fail + OIIO::geterror());
    const OIIO::ImageSpec spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.width > kMaxTextureSide || spec.height > kMaxTextureSide ||
        spec.depth > 1)
        throw Error(fail + "size " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                    " is outside 1.." + std::to_string(kMaxTextureSide));
    const int nc = spec.nchannels;
    if (nc < 1) throw Error(fail + "it has no channels");
    const std::size_t texels = std::size_t(spec.width) * std::size_t(spec.height);
    const auto base = spec.format.basetype;
    TextureImage t;
    t.width = spec.width;
    t.height = spec.height;
    t.is_float = base == OIIO::TypeDesc::HALF || base == OIIO::TypeDesc::FLOAT || base == OIIO::TypeDesc::DOUBLE;
    // Grey becomes grey RGB; grey+alpha keeps its alpha; extra channels are dropped.
    auto spread = [&](auto& out, const auto& in_px, auto one) {
        out.resize(texels * 4);
        for (std::size_t i = 0; i < texels; ++i) {
            const auto* p = &in_px[i * std::size_t(nc)];
            const bool grey = nc < 3;
            for (int c = 0; c < 3; ++c) out[i * 4 + c] = p[grey ? 0 : c];
            out[i * 4 + 3] = nc == 2 ? p[1] : nc >= 4 ? p[3] : one;
        }
    };
    if (t.is_float) {
        std::vector<float> px(texels * std::size_t(nc));
        if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, px.data())) throw Error(fail + in->geterror());
        spread(t.rgba32, px, 1.0f);
    } else {
        std::vector<std::uint8_t> px(texels * std::size_t(nc));
        if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::UINT8, px.data())) throw Error(fail + in->geterror());
        spread(t.rgba8, px, std::uint8_t(255));
    }
    return t;
#else
    throw Error(fail + "this build has no OpenImageIO");
#endif
}

}  // namespace clpath
