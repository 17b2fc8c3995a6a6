// The files a glTF document names (buffers, images), read through
// LoadOptions::read_file for tinygltf, and checked first so that a missing
// file or a URI that is not a relative path names its glTF entry.
#include <cctype>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "scene/load/gltf_parts.hpp"
#include "util/error.hpp"

namespace clpath::gltf {
namespace {

namespace fs = std::filesystem;

bool fs_exists(const std::string& path, void* user) {
    auto* f = static_cast<Files*>(user);
    if (f->data_uris && find_data_uri(*f->data_uris, path)) return true;
    if (f->options->file_exists) return f->options->file_exists(path);
    std::error_code ec;
    return fs::is_regular_file(path, ec);
}
std::string fs_expand(const std::string& path, void*) { return path; }
bool fs_read(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    auto* f = static_cast<Files*>(user);
    if (f->data_uris)
        if (auto* bytes = find_data_uri(*f->data_uris, path)) {
            *out = std::move(*bytes);  // read once, by the one buffer that names it
            return true;
        }
    try {
        const std::string s = f->options->read_file(path);
        out->assign(s.begin(), s.end());
        return true;
    } catch (const Error& e) {
        f->last_error = e.what();
        if (err) *err += e.what();
        return false;
    }
}
bool fs_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err += "writing is not supported";
    return false;
}

}  // namespace

std::string percent_decode(const std::string& s, bool& ok) {
    std::string out;
    ok = true;
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (s[i] != '%') {
            out += s[i];
            continue;
        }
        if (i + 2 >= s.size() || !std::isxdigit(static_cast<unsigned char>(s[i + 1])) ||
            !std::isxdigit(static_cast<unsigned char>(s[i + 2]))) {
            ok = false;
            return s;
        }
        out += char(std::stoi(s.substr(i + 1, 2), nullptr, 16));
        i += 2;
    }
    return out;
}

tinygltf::FsCallbacks file_callbacks(Files& files) { return {fs_exists, fs_expand, fs_read, fs_write, &files}; }

bool keep_encoded(tinygltf::Image* image, const int, std::string*, std::string*, int, int, const unsigned char* bytes,
                  int size, void*) {
    image->image.assign(bytes, bytes + size);
    image->as_is = true;
    return true;
}

std::string uri_path(const std::string& file, const std::string& uri) {
    bool ok;
    return (fs::path(file).parent_path() / percent_decode(uri, ok)).lexically_normal().string();
}

std::vector<std::string> check_uris(const nlohmann::json& doc, const std::string& file, const LoadOptions& options,
                                    DataUris& uris) {
    std::vector<std::string> warnings;
    for (const char* section : {"buffers", "images"}) {
        auto it = doc.find(section);
        if (it == doc.end() || !it->is_array()) continue;
        for (std::size_t i = 0; i < it->size(); ++i) {
            const auto& e = (*it)[i];
            if (!e.is_object() || !e.contains("uri") || !e["uri"].is_string()) continue;
            const std::string uri = e["uri"].get<std::string>();
            const std::string path = std::string(section) + "[" + std::to_string(i) + "].uri";
            auto fail = [&](const std::string& what) { throw Error(file + ": " + path + ": " + what); };
            if (uri.rfind("data:", 0) == 0) {
                if (uri.find(";base64,") == std::string::npos) fail("a data URI must be base64 (data:...;base64,...)");
                continue;
            }
            if (uri.rfind(kDataUriPrefix, 0) == 0) continue;  // decoded already (extract_data_uris)
            const auto colon = uri.find(':');
            if (uri.empty() || (colon != std::string::npos && colon < uri.find('/')) || uri[0] == '/')
                fail("'" + uri.substr(0, 80) + "' is not a relative file path or a data URI");
            bool ok;
            (void)percent_decode(uri, ok);
            if (!ok) fail("'" + uri.substr(0, 80) + "' has a bad %-escape");
            const std::string full = uri_path(file, uri);
            try {
                check_file_allowed(full);
            } catch (const Error& e) {
                fail(e.what());
            }
            Files f{&options, {}, &uris};
            if (fs_exists(full, &f)) continue;
            if (std::string(section) == "buffers") fail(full + ": no such file");
            // A missing image: as Blender does, the textures that use it are left
            // out (a neutral texture), with a warning; the geometry still loads.
            warnings.push_back(file + ": " + path + ": " + full +
                               ": no such file; the textures that use the image are left out");
        }
    }
    return warnings;
}

}  // namespace clpath::gltf
