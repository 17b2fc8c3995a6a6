#pragma once
// The pieces of OBJ and MTL lines the loader's line checks read: lines,
// whitespace-separated tokens, numbers, material names and paths.
#include <cstddef>
#include <cstring>
#include <string>
#include <string_view>

namespace clpath::obj_text {

// Inline, like next_line: they run for every byte of a million-line file.
inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// The next whitespace-separated token of s (empty at the end); s moves past it.
inline std::string_view next_token(std::string_view& s) {
    std::size_t i = 0;
    while (i < s.size() && is_space(s[i])) ++i;
    std::size_t j = i;
    while (j < s.size() && !is_space(s[j])) ++j;
    std::string_view tok = s.substr(i, j - i);
    s.remove_prefix(j);
    return tok;
}

// A material's name: the rest of its usemtl or newmtl line, less the
// whitespace around it, as assimp and Blender read it ("usemtl Hard Shiny
// Plastic" names one material).
std::string name_of(std::string_view rest);

// Files written on Windows name their libraries and images with backslashes
// (".\wood.jpg"); read as the folder separators they are, as Blender and
// assimp do.
std::string with_slashes(std::string path);

// The line starting at pos, without its end; pos moves past the end. Lines
// end where tinyobjloader ends them: at \n, \r or \r\n.
inline std::string_view next_line(const std::string& text, std::size_t& pos) {
    std::size_t end = text.find('\n', pos);  // memchr-fast, then \r within the line only
    if (end == std::string::npos) end = text.size();
    const void* cr = std::memchr(text.data() + pos, '\r', end - pos);
    if (cr) end = std::size_t(static_cast<const char*>(cr) - text.data());
    const std::string_view line(text.data() + pos, end - pos);
    pos = end;
    if (pos < text.size() && text[pos++] == '\r' && pos < text.size() && text[pos] == '\n') ++pos;
    return line;
}

// A whole token as a number, "+" allowed; 1e999 reads as HUGE_VAL (a number,
// just not a finite one: the caller says so).
bool parse_double(std::string_view t, double& out);

// The number a token starts with, for tokens such as "3.1+e2" that are not
// numbers as a whole: its length (0 when it starts with none) and value.
std::size_t parse_leading_double(std::string_view t, double& out);

bool parse_int(std::string_view t, long long& out);

}  // namespace clpath::obj_text
