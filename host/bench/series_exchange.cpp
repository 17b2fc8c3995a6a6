#include "bench/series_exchange.hpp"

#include <cstring>
#include <type_traits>

#include "render/process_group.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

static_assert(std::is_trivially_copyable_v<ConvergencePoint>, "points travel as bytes");

void put_text(std::string& out, const std::string& s) {
    const std::uint64_t n = s.size();
    out.append(reinterpret_cast<const char*>(&n), sizeof n);
    out += s;
}

class Reader {
public:
    explicit Reader(const std::string& bytes) : b_(bytes) {}
    bool done() const { return at_ == b_.size(); }
    void raw(void* dst, std::size_t n) {
        if (at_ + n > b_.size()) throw Error("internal: a truncated convergence series from another process");
        std::memcpy(dst, b_.data() + at_, n);
        at_ += n;
    }
    std::uint64_t count() {
        std::uint64_t n;
        raw(&n, sizeof n);
        return n;
    }
    std::string text() {
        std::string s(count(), '\0');
        raw(s.data(), s.size());
        return s;
    }

private:
    const std::string& b_;
    std::size_t at_ = 0;
};

}  // namespace

std::vector<ConvergenceSeries> gather_series(const std::vector<ConvergenceSeries>& mine,
                                             const std::vector<EstimatorConfig>& configs, ProcessGroup* group) {
    if (!group) return mine;
    std::string bytes;
    for (const auto& s : mine) {
        put_text(bytes, s.config);
        put_text(bytes, s.description);
        put_text(bytes, s.options);
        const std::uint64_t n = s.points.size();
        bytes.append(reinterpret_cast<const char*>(&n), sizeof n);
        bytes.append(reinterpret_cast<const char*>(s.points.data()), n * sizeof(ConvergencePoint));
    }
    std::vector<ConvergenceSeries> all;
    for (const std::string& from_rank : group->gather_bytes(bytes)) {
        Reader r(from_rank);
        while (!r.done()) {
            ConvergenceSeries s;
            s.config = r.text();
            s.description = r.text();
            s.options = r.text();
            s.points.resize(r.count());
            r.raw(s.points.data(), s.points.size() * sizeof(ConvergencePoint));
            all.push_back(std::move(s));
        }
    }
    std::vector<ConvergenceSeries> ordered;
    for (const auto& c : configs)
        for (auto& s : all)
            if (s.config == c.name) ordered.push_back(std::move(s));
    return ordered;
}

}  // namespace clpath
