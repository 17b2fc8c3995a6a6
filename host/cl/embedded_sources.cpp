#include "cl/embedded_sources.hpp"

#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <utility>

#include "util/error.hpp"

namespace clpath {
namespace {

using ByName = std::map<std::string, const char*>;

ByName index(const SourceTable& table) {
    ByName m;
    for (const auto& s : table) m.emplace(s.name, s.text);
    return m;
}

struct Assembler {
    ByName files;
    std::set<std::string> taken;
    std::string out;

    void include(const std::string& name, const std::string& from) {
        if (!taken.insert(name).second) return;
        auto it = files.find(name);
        if (it == files.end())
            throw Error("internal: kernel source " + name + (from.empty() ? "" : " (included from " + from + ")") +
                        " is not embedded");
        static const std::regex quoted(R"re(^\s*#\s*include\s*"([^"]+)"\s*$)re");
        std::istringstream in(it->second);
        std::string line;
        out += "#line 1 \"" + name + "\"\n";
        for (int n = 1; std::getline(in, line); ++n) {
            std::smatch m;
            if (std::regex_match(line, m, quoted)) {
                include(m[1].str(), name + ":" + std::to_string(n));
                out += "#line " + std::to_string(n + 1) + " \"" + name + "\"\n";
            } else {
                out += line;
                out += '\n';
            }
        }
    }
};

// The program from these files, root files in order.
std::string assemble(ByName files, const std::vector<std::string>& roots) {
    Assembler a;
    a.files = std::move(files);
    for (const auto& r : roots) a.include(r, "");
    return a.out;
}

}  // namespace

const std::string& embedded_source(const std::string& name) {
    static const std::map<std::string, std::string> by_name = [] {
        std::map<std::string, std::string> m;
        for (const auto& s : embedded_sources()) m.emplace(s.name, s.text);
        return m;
    }();
    auto it = by_name.find(name);
    if (it == by_name.end()) throw Error("internal: no embedded kernel source named " + name);
    return it->second;
}

std::string program_source(const std::vector<std::string>& roots, const SourceTable& extra) {
    ByName files = index(embedded_sources());
    for (const auto& s : extra)
        if (!files.emplace(s.name, s.text).second)
            throw Error(std::string("internal: two embedded kernel sources are named ") + s.name);
    return assemble(std::move(files), roots);
}

std::string variant_source(const std::vector<std::string>& roots, const KernelVariant& variant) {
    ByName files = index(embedded_sources());
    for (const auto& [name, text] : variant.files) {
        auto it = files.find(name);
        if (it == files.end()) throw Error(name + " is not one of clpath's kernel files, so it replaces none");
        it->second = text.c_str();  // the variant outlives the assembly
    }
    return assemble(std::move(files), roots);
}

std::string variant_options(const std::string& options, const KernelVariant& variant) {
    return variant.options.empty() ? options : options + " " + variant.options;
}

const std::vector<std::string>& renderer_kernel_files() {
    static const std::vector<std::string> files = {"integrator.cl"};
    return files;
}

const std::vector<std::string>& wavefront_kernel_files() {
    static const std::vector<std::string> files = {"wavefront.cl"};
    return files;
}

}  // namespace clpath
