#include <array>

#include "scene/load/gltf_parts.hpp"

namespace clpath::gltf {
namespace {

constexpr std::uint8_t kNotBase64 = 0xff;

std::array<std::uint8_t, 256> base64_table() {
    std::array<std::uint8_t, 256> t;
    t.fill(kNotBase64);
    const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for (std::uint8_t i = 0; i < 64; ++i) t[static_cast<unsigned char>(alphabet[i])] = i;
    return t;
}

// RFC 4648 base64 (padding optional); false on any other character.
bool decode_base64(const char* p, std::size_t n, std::vector<unsigned char>& out) {
    static const std::array<std::uint8_t, 256> table = base64_table();
    while (n > 0 && p[n - 1] == '=') --n;
    if (n % 4 == 1) return false;
    out.clear();
    out.reserve(n / 4 * 3 + 2);
    std::uint32_t acc = 0;
    int bits = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint8_t v = table[static_cast<unsigned char>(p[i])];
        if (v == kNotBase64) return false;
        acc = (acc << 6) | v;
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out.push_back(static_cast<unsigned char>(acc >> bits));
        }
    }
    return true;
}

bool skip_space(const std::string& s, std::size_t& i) {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == '\n' || s[i] == '\r')) ++i;
    return i < s.size();
}

}  // namespace

std::string extract_data_uris(const std::string& text, DataUris& uris) {
    static const std::string key = "\"uri\"", data = "data:", marker = ";base64,";
    std::string out;
    std::size_t copied = 0, at = 0;
    while ((at = text.find(key, at)) != std::string::npos) {
        std::size_t i = at + key.size();
        at = i;
        if (!skip_space(text, i) || text[i] != ':') continue;
        ++i;
        if (!skip_space(text, i) || text[i] != '"' || text.compare(i + 1, data.size(), data) != 0) continue;
        const std::size_t open = i;  // the value's opening quote
        const std::size_t close = text.find('"', open + 1);
        const std::size_t comma = text.find(marker, open + 1);
        if (close == std::string::npos || comma == std::string::npos || comma > close) continue;
        const std::string media = text.substr(open + 1 + data.size(), comma - open - 1 - data.size());
        // Images keep their URI: the media type tells the decoder the format.
        if (media.rfind("image/", 0) == 0) continue;
        std::vector<unsigned char> bytes;
        const std::size_t from = comma + marker.size();
        // An escaped character (a JSON writer may write "\/") or anything else
        // that is not base64: left to tinygltf, which reports it.
        if (!decode_base64(text.data() + from, close - from, bytes)) continue;
        const std::string name = kDataUriPrefix + std::to_string(uris.size() + 1) + ")";
        uris.emplace_back(name, std::move(bytes));
        out.append(text, copied, open + 1 - copied);
        out += name;
        copied = close;  // from the closing quote on
        at = close + 1;
    }
    if (copied == 0) return text;
    out.append(text, copied, std::string::npos);
    return out;
}

std::vector<unsigned char>* find_data_uri(DataUris& uris, const std::string& path) {
    const auto at = path.rfind(kDataUriPrefix);
    if (at == std::string::npos || (at > 0 && path[at - 1] != '/')) return nullptr;
    const std::string name = path.substr(at);
    for (auto& [n, bytes] : uris)
        if (n == name) return &bytes;
    return nullptr;
}

}  // namespace clpath::gltf
