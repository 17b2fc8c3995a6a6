#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include "image/image.hpp"
#include "util/error.hpp"

#ifdef CLPATH_WITH_OIIO
#include <OpenImageIO/imageio.h>
#endif

namespace clpath {
namespace fs = std::filesystem;
namespace {

std::string extension(const std::string& path) {
    std::string e = fs::path(path).extension().string();
    std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
    return e;
}

fs::path temp_beside(const fs::path& p) {
    // Same folder (so rename is atomic) and same extension (OpenImageIO picks the format from it).
    return p.parent_path() / (std::string(".") + p.stem().string() + ".tmp" + std::to_string(::getpid()) + p.extension().string());
}

#ifdef CLPATH_WITH_OIIO
float srgb_decode(float v) { return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f); }
#endif

}  // namespace

void check_output_path(const std::string& path) {
    std::error_code ec;
    // A folder first: its "extension" would otherwise read as an unknown format.
    if (!path.empty() && (path.back() == '/' || fs::is_directory(path, ec))) {
        const std::string dir = path.back() == '/' ? path : path + "/";
        const bool exists = fs::is_directory(path, ec);
        throw UsageError("output " + path + ": is a folder" + (exists ? "" : " name (and no such folder exists)") +
                         "; name an image file in it, such as " + dir + "image.png");
    }
    const std::string ext = extension(path);
    if (ext != ".png" && ext != ".exr" && ext != ".pfm")
        throw UsageError("output " + path + ": unknown image format '" + ext + "' (use .png, .exr or .pfm)");
#ifndef CLPATH_WITH_OIIO
    if (ext != ".pfm")
        throw UsageError("output " + path + ": this build has no OpenImageIO, so it writes .pfm only");
#endif
    fs::path dir = fs::path(path).parent_path();
    if (dir.empty()) dir = ".";
    if (!fs::is_directory(dir, ec))
        throw UsageError("output " + path + ": folder " + dir.string() + " does not exist");
    if (::access(dir.c_str(), W_OK) != 0)
        throw UsageError("output " + path + ": folder " + dir.string() + " is not writable");
}

void write_pfm(const std::string& path, const Image& img) {
    std::ofstream out(path, std::ios::binary);
    if (!out) throw Error("cannot write " + path + ": " + std::strerror(errno));
    // PFM: bottom row first, negative scale = little-endian.
    out << "PF\n" << img.width << " " << img.height << "\n-1.0\n";
    for (int y = img.height - 1; y >= 0; --y)
        out.write(reinterpret_cast<const char*>(&img.rgb[std::size_t(y) * img.width * 3]),
                  std::streamsize(img.width * 3 * sizeof(float)));
    if (!out) throw Error("cannot write " + path + ": write failed");
}

Image read_pfm(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error("cannot read " + path + ": " + std::strerror(errno));
    std::string magic;
    Image img;
    double scale = 0;
    in >> magic >> img.width >> img.height >> scale;
    in.get();
    if (!in || magic != "PF" || img.width <= 0 || img.height <= 0 || img.width > 65536 || img.height > 65536)
        throw Error(path + ": not a colour PFM file (expected 'PF', width, height, scale)");
    if (scale > 0) throw Error(path + ": big-endian PFM is not supported");
    img.rgb.resize(std::size_t(img.width) * img.height * 3);
    for (int y = img.height - 1; y >= 0; --y)
        in.read(reinterpret_cast<char*>(&img.rgb[std::size_t(y) * img.width * 3]),
                std::streamsize(img.width * 3 * sizeof(float)));
    if (!in) throw Error(path + ": file ends before its last pixel");
    return img;
}

void write_image(const std::string& path, const RenderedImage& image) {
    check_output_path(path);
    const fs::path tmp = temp_beside(path);
    const std::string ext = extension(path);
    try {
        if (ext == ".pfm") {
            write_pfm(tmp.string(), image.linear);
        } else {
#ifdef CLPATH_WITH_OIIO
            auto out = OIIO::ImageOutput::create(tmp.string());
            if (!out) throw Error("cannot write " + path + ": " + OIIO::geterror());
            const Image& lin = image.linear;
            bool ok;
            if (ext == ".png") {
                OIIO::ImageSpec spec(lin.width, lin.height, 4, OIIO::TypeDesc::UINT8);
                spec.attribute("oiio:ColorSpace", "sRGB");
                ok = out->open(tmp.string(), spec) && out->write_image(OIIO::TypeDesc::UINT8, image.srgb8.data());
            } else {
                OIIO::ImageSpec spec(lin.width, lin.height, 3, OIIO::TypeDesc::FLOAT);
                spec.attribute("oiio:ColorSpace", "Linear");
                spec.attribute("compression", "zip");
                ok = out->open(tmp.string(), spec) && out->write_image(OIIO::TypeDesc::FLOAT, lin.rgb.data());
            }
            ok = out->close() && ok;
            if (!ok) throw Error("cannot write " + path + ": " + out->geterror());
#endif
        }
        std::error_code ec;
        fs::rename(tmp, path, ec);
        if (ec) throw Error("cannot write " + path + ": " + ec.message());
    } catch (...) {
        std::error_code ec;
        fs::remove(tmp, ec);
        throw;
    }
}

void check_image_readable(const std::string& path) {
    if (extension(path) == ".pfm") {
        std::ifstream in(path, std::ios::binary);
        std::string magic;
        if (!(in >> magic) || magic != "PF") throw Error(path + ": not a colour PFM file (expected 'PF', width, height, scale)");
        return;
    }
#ifdef CLPATH_WITH_OIIO
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw Error("cannot read " + path + " as an image: " + OIIO::geterror());
    if (in->spec().nchannels < 3)
        throw Error(path + ": expected an RGB image, found " + std::to_string(in->spec().nchannels) + " channels");
#else
    throw Error("cannot read " + path + ": this build has no OpenImageIO, so it reads .pfm only");
#endif
}

Image read_image(const std::string& path) {
    if (extension(path) == ".pfm") return read_pfm(path);
#ifdef CLPATH_WITH_OIIO
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw Error("cannot read " + path + ": " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.nchannels < 1) throw Error(path + ": the image has no channels");
    // One channel (or grey and alpha) is a grey image: its value in R, G and B.
    const int grey = spec.nchannels < 3 ? 1 : 0;
    std::vector<float> all(std::size_t(spec.width) * spec.height * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, all.data()))
        throw Error("cannot read " + path + ": " + in->geterror());
    const bool encoded = spec.format.basetype == OIIO::TypeDesc::UINT8 || spec.format.basetype == OIIO::TypeDesc::UINT16;
    Image img;
    img.width = spec.width;
    img.height = spec.height;
    img.rgb.resize(std::size_t(spec.width) * spec.height * 3);
    for (std::size_t i = 0; i < std::size_t(spec.width) * spec.height; ++i)
        for (int c = 0; c < 3; ++c) {
            float v = all[i * spec.nchannels + (grey ? 0 : c)];
            img.rgb[i * 3 + c] = encoded ? srgb_decode(v) : v;
        }
    return img;
#else
    throw Error("cannot read " + path + ": this build has no OpenImageIO, so it reads .pfm only");
#endif
}

}  // namespace clpath
