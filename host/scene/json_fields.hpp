#pragma once
// Strict reading of JSON documents: every value knows where it sits
// ("scenes/x.json: objects[2].transform.scale"), so that a wrong type, a value
// out of range or a field nobody reads is reported by its path, and never
// silently ignored.
#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace clpath::jsonf {

// Ordered: materials keep the order the file gives them, and messages follow it.
using json = nlohmann::ordered_json;

// s as a JSON string literal, quoted and escaped (invalid UTF-8 replaced),
// for the files clpath writes.
std::string quote(const std::string& s);

// Parses text as JSON; a syntax error is reported as "FILE:LINE:COLUMN: ...",
// a key given twice in one object as "FILE: path: ...".
json parse(const std::string& text, const std::string& file);

// A position in a document, for messages.
struct Where {
    std::string file;
    std::string path;  // empty: the document itself
    Where key(const std::string& k) const;
    Where index(std::size_t i) const;
    std::string str() const;  // "FILE: path" or "FILE"
    [[noreturn]] void fail(const std::string& what) const;
};

// An interval for number checks; its text is what messages show ("(0, 180)").
struct Range {
    double lo, hi;
    bool lo_open = false, hi_open = false;
    bool contains(double v) const;
    std::string str() const;
};
inline constexpr double kHuge = 1e30;  // no float value a scene needs is larger
inline const Range kAny{-kHuge, kHuge};
inline const Range kNonNegative{0, kHuge};
inline const Range kPositive{0, kHuge, true, false};
inline const Range kUnit{0, 1};

// One value and its place. Readers fail with the place in the message.
class Value {
public:
    Value(const json& j, Where w) : j_(&j), w_(std::move(w)) {}
    const json& raw() const { return *j_; }
    const Where& where() const { return w_; }
    [[noreturn]] void fail(const std::string& what) const { w_.fail(what); }

    double number(const Range& r = kAny) const;  // finite, within r
    float real(const Range& r = kAny) const;     // as number(), and finite as a float
    std::int64_t integer(std::int64_t lo, std::int64_t hi) const;
    bool boolean() const;
    std::string string() const;
    // Exactly three numbers, each within r.
    glm::vec3 vec3(const Range& r = kAny) const;
    // [r, g, b] or one number for a grey, each within r.
    glm::vec3 color(const Range& r) const;
    // A number for all three axes, or [x, y, z].
    glm::vec3 scalar_or_vec3(const Range& r) const;
    std::vector<Value> array() const;
    const char* type_name() const;

private:
    const json* j_;
    Where w_;
};

// A JSON object read field by field. finish() rejects every field that no
// get() asked for, naming it and the fields that are allowed.
class Object {
public:
    Object(const Value& v);  // fails unless v is an object
    const Where& where() const { return w_; }
    bool has(const std::string& key) const;
    std::optional<Value> get(const std::string& key);
    Value require(const std::string& key);
    // The one of several synonyms present (at most one may be), e.g. albedo / color.
    std::optional<Value> get_one_of(const std::vector<std::string>& keys);
    // Every field in document order, for objects that are maps (materials).
    std::vector<std::pair<std::string, Value>> entries() const;
    void finish() const;

private:
    const json* j_;
    Where w_;
    std::set<std::string> asked_;
};

}  // namespace clpath::jsonf
