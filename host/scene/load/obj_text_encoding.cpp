#include "scene/load/obj_text_encoding.hpp"

#include <cstdint>

#include "util/error.hpp"

namespace clpath {
namespace {

void append_utf8(std::string& out, std::uint32_t c) {
    if (c < 0x80) {
        out += char(c);
    } else if (c < 0x800) {
        out += char(0xC0 | (c >> 6));
        out += char(0x80 | (c & 0x3F));
    } else if (c < 0x10000) {
        out += char(0xE0 | (c >> 12));
        out += char(0x80 | ((c >> 6) & 0x3F));
        out += char(0x80 | (c & 0x3F));
    } else {
        out += char(0xF0 | (c >> 18));
        out += char(0x80 | ((c >> 12) & 0x3F));
        out += char(0x80 | ((c >> 6) & 0x3F));
        out += char(0x80 | (c & 0x3F));
    }
}

}  // namespace

std::string obj_text_as_utf8(std::string bytes, const std::string& file) {
    auto starts = [&](std::initializer_list<unsigned char> mark) {
        if (bytes.size() < mark.size()) return false;
        std::size_t i = 0;
        for (unsigned char m : mark)
            if ((unsigned char)bytes[i++] != m) return false;
        return true;
    };
    if (starts({0xEF, 0xBB, 0xBF})) return std::string(bytes.begin() + 3, bytes.end());
    const bool le = starts({0xFF, 0xFE}), be = starts({0xFE, 0xFF});
    if (!le && !be) return bytes;
    if (bytes.size() % 2) throw Error(file + ": UTF-16 text with an odd number of bytes (cut short?)");
    std::string out;
    out.reserve(bytes.size() / 2);
    auto unit = [&](std::size_t i) -> std::uint32_t {
        const std::uint32_t a = (unsigned char)bytes[i], b = (unsigned char)bytes[i + 1];
        return le ? a | (b << 8) : (a << 8) | b;
    };
    for (std::size_t i = 2; i < bytes.size(); i += 2) {
        std::uint32_t c = unit(i);
        if (c >= 0xD800 && c < 0xDC00) {  // a high surrogate: its low one must follow
            const std::uint32_t lo = i + 2 < bytes.size() ? unit(i + 2) : 0;
            if (lo < 0xDC00 || lo >= 0xE000)
                throw Error(file + ": UTF-16 text with an unpaired surrogate at byte " + std::to_string(i));
            c = 0x10000 + ((c - 0xD800) << 10) + (lo - 0xDC00);
            i += 2;
        } else if (c >= 0xDC00 && c < 0xE000) {
            throw Error(file + ": UTF-16 text with an unpaired surrogate at byte " + std::to_string(i));
        }
        append_utf8(out, c);
    }
    return out;
}

}  // namespace clpath
