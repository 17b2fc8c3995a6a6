#include "scene/json_fields.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

#include "util/error.hpp"

namespace clpath::jsonf {

std::string quote(const std::string& s) {
    return nlohmann::json(s).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

namespace {

std::string format_number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

// nlohmann reports a byte offset; people look for lines and columns.
std::string line_column(const std::string& text, std::size_t byte) {
    if (byte == 0) byte = 1;
    const std::size_t end = std::min(byte - 1, text.size());
    std::size_t line = 1, line_start = 0;
    for (std::size_t i = 0; i < end; ++i)
        if (text[i] == '\n') {
            ++line;
            line_start = i + 1;
        }
    return std::to_string(line) + ":" + std::to_string(end - line_start + 1);
}

// nlohmann's what() starts with "[json.exception.parse_error.101] parse error at
// line 3, column 5: "; the position goes in front in the usual FILE:LINE:COL form.
std::string bare_message(const std::string& what) {
    std::string m = what;
    if (m.rfind("[json.exception.", 0) == 0) {
        const auto close = m.find("] ");
        if (close != std::string::npos) m = m.substr(close + 2);
    }
    if (m.rfind("parse error", 0) == 0) {
        const auto colon = m.find(": ");
        if (colon != std::string::npos) m = m.substr(colon + 2);
    }
    return m;
}

// Where the parser is, so that a repeated key can be named by its path.
struct Frame {
    bool array = false;
    std::size_t index = 0;
    std::string key;
    std::set<std::string> keys;
};

std::string path_of(const std::vector<Frame>& stack) {
    Where w;
    for (std::size_t i = 0; i + 1 < stack.size(); ++i)
        w = stack[i].array ? w.index(stack[i].index) : w.key(stack[i].key);
    return w.path;
}

void advance(std::vector<Frame>& stack) {
    if (!stack.empty() && stack.back().array) ++stack.back().index;
}

}  // namespace

json parse(const std::string& text, const std::string& file) {
    // nlohmann keeps the last of two equal keys without a word; a scene with a
    // key twice is almost always a copy-paste mistake, so it is an error.
    std::vector<Frame> stack;
    auto callback = [&](int, json::parse_event_t ev, json& parsed) {
        switch (ev) {
        case json::parse_event_t::object_start: stack.push_back({}); break;
        case json::parse_event_t::array_start: {
            Frame f;
            f.array = true;
            stack.push_back(f);
            break;
        }
        case json::parse_event_t::key: {
            const std::string k = parsed.get<std::string>();
            Frame& top = stack.back();
            const bool repeated = !top.keys.insert(k).second;
            top.key = k;
            if (repeated) {
                // A frame past the key makes the path name the key itself. (It is
                // pushed after the last use of `top`, which it may move.)
                stack.emplace_back();
                Where{file, path_of(stack)}.fail("field given twice");
            }
            break;
        }
        case json::parse_event_t::object_end:
        case json::parse_event_t::array_end:
            stack.pop_back();
            advance(stack);
            break;
        case json::parse_event_t::value: advance(stack); break;
        }
        return true;
    };
    try {
        return json::parse(text, callback);
    } catch (const json::parse_error& e) {
        throw Error(file + ":" + line_column(text, e.byte) + ": " + bare_message(e.what()));
    } catch (const json::exception& e) {
        throw Error(file + ": " + bare_message(e.what()));
    }
}

Where Where::key(const std::string& k) const { return {file, path.empty() ? k : path + "." + k}; }
Where Where::index(std::size_t i) const { return {file, path + "[" + std::to_string(i) + "]"}; }
std::string Where::str() const { return path.empty() ? file : file + ": " + path; }
void Where::fail(const std::string& what) const { throw Error(str() + ": " + what); }

bool Range::contains(double v) const {
    return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
}

std::string Range::str() const {
    if (lo <= -kHuge && hi >= kHuge) return "any finite number";
    if (hi >= kHuge) return (lo_open ? "> " : ">= ") + format_number(lo);
    return std::string(lo_open ? "(" : "[") + format_number(lo) + ", " + format_number(hi) + (hi_open ? ")" : "]");
}

const char* Value::type_name() const { return j_->type_name(); }

double Value::number(const Range& r) const {
    if (!j_->is_number()) fail(std::string("expected a number, got ") + type_name());
    const double v = j_->get<double>();
    if (!std::isfinite(v)) fail("must be a finite number");
    if (!r.contains(v)) fail(format_number(v) + " is out of range (must be " + r.str() + ")");
    return v;
}

float Value::real(const Range& r) const {
    const double v = number(r);
    if (std::fabs(v) > double(std::numeric_limits<float>::max())) fail("too large for a float");
    return float(v);
}

std::int64_t Value::integer(std::int64_t lo, std::int64_t hi) const {
    if (!j_->is_number()) fail(std::string("expected an integer, got ") + type_name());
    std::int64_t v;
    if (j_->is_number_unsigned()) {
        const auto u = j_->get<std::uint64_t>();
        v = u > std::uint64_t(std::numeric_limits<std::int64_t>::max()) ? std::numeric_limits<std::int64_t>::max()
                                                                          : std::int64_t(u);
    } else if (j_->is_number_integer()) {
        v = j_->get<std::int64_t>();
    } else {
        // 2.0 is as good as 2; 2.5 is not an integer.
        const double d = j_->get<double>();
        if (!std::isfinite(d) || d != std::floor(d) || std::fabs(d) > 9e15)
            fail("expected an integer, got " + format_number(d));
        v = std::int64_t(d);
    }
    if (v < lo || v > hi)
        fail(std::to_string(v) + " is out of range (must be in [" + std::to_string(lo) + ", " + std::to_string(hi) +
             "])");
    return v;
}

bool Value::boolean() const {
    if (!j_->is_boolean()) fail(std::string("expected true or false, got ") + type_name());
    return j_->get<bool>();
}

std::string Value::string() const {
    if (!j_->is_string()) fail(std::string("expected a string, got ") + type_name());
    return j_->get<std::string>();
}

std::vector<Value> Value::array() const {
    if (!j_->is_array()) fail(std::string("expected an array, got ") + type_name());
    std::vector<Value> out;
    out.reserve(j_->size());
    for (std::size_t i = 0; i < j_->size(); ++i) out.emplace_back((*j_)[i], w_.index(i));
    return out;
}

glm::vec3 Value::vec3(const Range& r) const {
    if (!j_->is_array() || j_->size() != 3)
        fail(std::string("expected an array of three numbers [x, y, z], got ") +
             (j_->is_array() ? "an array of " + std::to_string(j_->size()) : std::string(type_name())));
    const auto a = array();
    return {a[0].real(r), a[1].real(r), a[2].real(r)};
}

glm::vec3 Value::color(const Range& r) const {
    if (j_->is_number()) return glm::vec3(real(r));
    if (!j_->is_array() || j_->size() != 3)
        fail(std::string("expected a colour [r, g, b] or one number, got ") +
             (j_->is_array() ? "an array of " + std::to_string(j_->size()) : std::string(type_name())));
    return vec3(r);
}

glm::vec3 Value::scalar_or_vec3(const Range& r) const {
    if (j_->is_number()) return glm::vec3(real(r));
    if (!j_->is_array() || j_->size() != 3)
        fail(std::string("expected a number or [x, y, z], got ") +
             (j_->is_array() ? "an array of " + std::to_string(j_->size()) : std::string(type_name())));
    return vec3(r);
}

Object::Object(const Value& v) : j_(&v.raw()), w_(v.where()) {
    if (!j_->is_object()) v.fail(std::string("expected an object { ... }, got ") + v.type_name());
}

bool Object::has(const std::string& key) const { return j_->contains(key); }

std::optional<Value> Object::get(const std::string& key) {
    asked_.insert(key);
    auto it = j_->find(key);
    if (it == j_->end()) return std::nullopt;
    return Value(*it, w_.key(key));
}

Value Object::require(const std::string& key) {
    auto v = get(key);
    if (!v) w_.key(key).fail("required field is missing");
    return *v;
}

std::optional<Value> Object::get_one_of(const std::vector<std::string>& keys) {
    std::optional<Value> found;
    std::string found_key;
    for (const auto& k : keys)
        if (auto v = get(k)) {
            if (found) v->fail("give only one of '" + found_key + "' and '" + k + "' (they mean the same)");
            found = v;
            found_key = k;
        }
    return found;
}

std::vector<std::pair<std::string, Value>> Object::entries() const {
    std::vector<std::pair<std::string, Value>> out;
    for (auto it = j_->begin(); it != j_->end(); ++it) out.emplace_back(it.key(), Value(it.value(), w_.key(it.key())));
    return out;
}

void Object::finish() const {
    for (auto it = j_->begin(); it != j_->end(); ++it) {
        if (asked_.count(it.key())) continue;
        std::string allowed;
        for (const auto& k : asked_) allowed += (allowed.empty() ? "" : ", ") + k;
        w_.key(it.key()).fail("unknown field" + (allowed.empty() ? std::string() : " (allowed here: " + allowed + ")"));
    }
}

}  // namespace clpath::jsonf
