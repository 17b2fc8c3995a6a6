#include "cl/offline_compile.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <regex>
#include <sstream>

#include "cl/program.hpp"
#include "util/error.hpp"

namespace clpath {
namespace fs = std::filesystem;
namespace {

std::string find_on_path(const std::string& name) {
    const char* path = std::getenv("PATH");
    std::istringstream dirs(path ? path : "");
    std::string dir;
    while (std::getline(dirs, dir, ':')) {
        if (dir.empty()) continue;
        const fs::path p = fs::path(dir) / name;
        std::error_code ec;
        if (fs::is_regular_file(p, ec) && access(p.c_str(), X_OK) == 0) return p.string();
    }
    return "";
}

std::string env_or(const char* name, const std::string& fallback) {
    const char* v = std::getenv(name);
    return v && *v ? v : fallback;
}

std::string read_file(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

void write_file(const fs::path& p, const std::string& text) {
    std::ofstream out(p, std::ios::binary);
    out << text;
    if (!out) throw Error("cannot write " + p.string());
}

// Single quotes for /bin/sh.
std::string quote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

std::string split_options(const std::string& options) {
    std::istringstream in(options);
    std::string word, out;
    while (in >> word) out += " " + quote(word);
    return out;
}

// Runs a command with its output (stdout and stderr) in log; returns its exit status.
int run(const std::string& command, const fs::path& log) {
    const int rc = std::system((command + " > " + quote(log.string()) + " 2>&1").c_str());
    if (rc == -1) return -1;
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : 128 + (WIFSIGNALED(rc) ? WTERMSIG(rc) : 0);
}

std::string version_line(const std::string& tool) {
    if (tool.empty()) return "missing";
    const fs::path tmp = fs::temp_directory_path() / ("clpath-version-" + std::to_string(getpid()) + ".txt");
    run(quote(tool) + " --version", tmp);
    std::istringstream in(read_file(tmp));
    fs::remove(tmp);
    std::string line, best;
    while (std::getline(in, line))
        if (line.find("version") != std::string::npos || line.find("release") != std::string::npos) {
            best = line;
            if (line.find("release") != std::string::npos) break;  // ptxas: "Cuda compilation tools, release 13.0, ..."
        }
    while (!best.empty() && (best.front() == ' ')) best.erase(0, 1);
    return best.empty() ? "unknown" : best;
}

// The per-target pipeline's tools.
struct Pipeline {
    std::string clang, link, opt, llc, nm, libclc, triple, cpu;
    bool nvidia;
};

Pipeline pipeline(const OfflineToolchain& t, const std::string& target) {
    Pipeline p;
    p.nvidia = is_nvidia_target(target);
    const bool llvm15 = target == "gfx1100";
    p.clang = llvm15 ? t.clang15 : t.clang14;
    p.link = llvm15 ? t.link15 : t.link14;
    p.opt = llvm15 ? t.opt15 : t.opt14;
    p.llc = llvm15 ? t.llc15 : t.llc14;
    p.nm = llvm15 ? t.nm15 : t.nm14;
    p.libclc = t.libclc_dir + (p.nvidia ? "/nvptx64--nvidiacl.bc" : "/amdgcn--amdhsa.bc");
    p.triple = p.nvidia ? "nvptx64-nvidia-nvcl" : "amdgcn-amd-amdhsa";
    p.cpu = target;
    return p;
}

// Results on disk, one small text file per key.
std::string serialise(const OfflineResult& r) {
    std::ostringstream o;
    o << (r.ok ? "ok" : "failed") << "\n" << r.kernels.size() << "\n";
    for (const auto& k : r.kernels)
        o << k.kernel << " " << k.registers << " " << k.sgprs << " " << k.stack_bytes << " " << k.spill_bytes << "\n";
    o << r.log;
    return o.str();
}

bool deserialise(const std::string& text, OfflineResult& r) {
    std::istringstream in(text);
    std::string status;
    std::size_t n = 0;
    if (!(in >> status >> n) || (status != "ok" && status != "failed")) return false;
    r.ok = status == "ok";
    r.kernels.resize(n);
    for (auto& k : r.kernels)
        if (!(in >> k.kernel >> k.registers >> k.sgprs >> k.stack_bytes >> k.spill_bytes)) return false;
    in.get();
    std::ostringstream rest;
    rest << in.rdbuf();
    r.log = rest.str();
    return true;
}

}  // namespace

const std::vector<std::string>& gpu_target_names() {
    static const std::vector<std::string> t = {"sm_90", "gfx90a", "gfx1100"};
    return t;
}

bool is_nvidia_target(const std::string& target) { return target.rfind("sm_", 0) == 0; }

OfflineToolchain find_offline_toolchain() {
    OfflineToolchain t;
    t.clang14 = find_on_path("clang-14");
    t.link14 = find_on_path("llvm-link-14");
    t.opt14 = find_on_path("opt-14");
    t.llc14 = find_on_path("llc-14");
    t.nm14 = find_on_path("llvm-nm-14");
    t.clang15 = find_on_path("clang-15");
    t.link15 = find_on_path("llvm-link-15");
    t.opt15 = find_on_path("opt-15");
    t.llc15 = find_on_path("llc-15");
    t.nm15 = find_on_path("llvm-nm-15");
    std::string ptxas = find_on_path("ptxas");
    if (ptxas.empty() && access("/usr/local/cuda/bin/ptxas", X_OK) == 0) ptxas = "/usr/local/cuda/bin/ptxas";
    t.ptxas = env_or("CLPATH_PTXAS", ptxas);
    t.libclc_dir = env_or("CLPATH_LIBCLC_DIR", "/usr/lib/clc");
    return t;
}

std::string missing_tools(const OfflineToolchain& t, const std::string& target) {
    const Pipeline p = pipeline(t, target);
    const char* llvm = target == "gfx1100" ? "15" : "14";
    std::string missing;
    auto need = [&](const std::string& path, const std::string& what) {
        if (path.empty()) missing += (missing.empty() ? "" : ", ") + what;
    };
    need(p.clang, std::string("clang-") + llvm);
    need(p.link, std::string("llvm-link-") + llvm);
    need(p.opt, std::string("opt-") + llvm);
    need(p.llc, std::string("llc-") + llvm);
    need(p.nm, std::string("llvm-nm-") + llvm);
    std::error_code ec;
    if (!fs::is_regular_file(p.libclc, ec)) missing += (missing.empty() ? "" : ", ") + ("libclc (" + p.libclc + ")");
    if (p.nvidia) need(t.ptxas, "ptxas (CUDA toolkit; or set CLPATH_PTXAS)");
    return missing;
}

std::string toolchain_versions(const OfflineToolchain& t) {
    return "clang-14: " + version_line(t.clang14) + "\nclang-15: " + version_line(t.clang15) +
           "\nllc-14: " + version_line(t.llc14) + "\nllc-15: " + version_line(t.llc15) +
           "\nptxas: " + version_line(t.ptxas) + "\nlibclc: " + t.libclc_dir + "\n";
}

OfflineResult compile_offline(const OfflineToolchain& tools, const std::string& target, const std::string& source,
                              const std::string& options, const std::string& work_dir, const std::string& cache_dir) {
    OfflineResult r;
    r.target = target;
    const std::string missing = missing_tools(tools, target);
    if (!missing.empty()) {
        r.log = "missing: " + missing;
        return r;
    }
    const Pipeline p = pipeline(tools, target);
    fs::path cache_file;
    if (!cache_dir.empty()) {
        // The tools' paths stand in for their versions: a cache lives in one build folder.
        static std::mutex m;
        static std::string versions;
        {
            std::lock_guard<std::mutex> lock(m);
            if (versions.empty()) versions = toolchain_versions(tools);
        }
        const std::uint64_t key = fnv1a64(source, fnv1a64(options + "\n" + target + "\n" + versions));
        char name[32];
        std::snprintf(name, sizeof name, "%016llx.txt", static_cast<unsigned long long>(key));
        fs::create_directories(cache_dir);
        cache_file = fs::path(cache_dir) / name;
        std::error_code ec;
        if (fs::is_regular_file(cache_file, ec) && deserialise(read_file(cache_file), r)) {
            r.target = target;
            r.from_cache = true;
            return r;
        }
    }
    const auto start = std::chrono::steady_clock::now();
    const fs::path dir(work_dir);
    fs::create_directories(dir);
    write_file(dir / "program.cl", source);
    write_file(dir / "options.txt", options + "\n");
    struct Step {
        std::string name, command;
    };
    const std::string bc = quote((dir / "program.bc").string()), linked = quote((dir / "linked.bc").string()),
                      opt = quote((dir / "opt.bc").string());
    std::vector<Step> steps = {
        {"clang", quote(p.clang) + " -x cl -Xclang -finclude-default-header -target " + p.triple +
                      (p.nvidia ? "" : " -mcpu=" + p.cpu + " -nogpulib") + " -O3 -emit-llvm -c" +
                      split_options(options) + " " + quote((dir / "program.cl").string()) + " -o " + bc},
        {"llvm-link", quote(p.link) + " " + bc + " " + quote(p.libclc) + " -o " + linked},
        {"opt", quote(p.opt) + " -O3 " + linked + " -o " + opt},
        {"llvm-nm", quote(p.nm) + " --undefined-only " + opt},
    };
    if (p.nvidia) {
        // LLVM 14 writes PTX up to ISA 7.5 for sm_80 at most; ptxas compiles that for sm_90.
        steps.push_back({"llc", quote(p.llc) + " -mcpu=sm_80 -mattr=+ptx75 " + opt + " -o " +
                                    quote((dir / "program.ptx").string())});
        steps.push_back({"ptxas", quote(tools.ptxas) + " -arch=" + target + " -v " +
                                      quote((dir / "program.ptx").string()) + " -o " +
                                      quote((dir / "program.cubin").string())});
    } else {
        steps.push_back({"llc", quote(p.llc) + " -mtriple=" + p.triple + " -mcpu=" + p.cpu + " " + opt + " -o " +
                                    quote((dir / "program.s").string())});
    }
    for (const auto& s : steps) {
        const fs::path log = dir / (s.name + ".log");
        const int rc = run(s.command, log);
        const std::string out = read_file(log);
        if (rc != 0) {
            r.log = s.name + " failed (exit status " + std::to_string(rc) + "):\n" + out;
            break;
        }
        if (s.name == "llvm-nm") {
            const auto undefined = parse_undefined_symbols(out);
            if (!undefined.empty()) {
                r.log = "unresolved symbols after linking libclc:";
                for (const auto& u : undefined) r.log += " " + u;
                r.log += "\n";
                break;
            }
        }
        if (s.name == "ptxas") {
            r.kernels = parse_ptxas_report(out);
            r.ok = true;
        }
        if (s.name == "llc" && !p.nvidia) {
            r.kernels = parse_amdgpu_metadata(read_file(dir / "program.s"));
            r.ok = true;
        }
    }
    if (r.ok && r.kernels.empty()) {
        r.ok = false;
        r.log = "no kernel found in the compiler's report";
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!cache_file.empty()) write_file(cache_file, serialise(r));
    return r;
}

std::vector<KernelResources> parse_ptxas_report(const std::string& text) {
    // ptxas info    : Compiling entry function 'k' for 'sm_90'
    // ptxas info    : Function properties for k
    //     544 bytes stack frame, 0 bytes spill stores, 0 bytes spill loads
    // ptxas info    : Used 95 registers, used 0 barriers, 544 bytes cumulative stack size
    static const std::regex entry(R"(Compiling entry function '([^']+)')");
    static const std::regex frame(R"((\d+) bytes stack frame, (\d+) bytes spill stores, (\d+) bytes spill loads)");
    static const std::regex used(R"(Used (\d+) registers)");
    static const std::regex cumulative(R"((\d+) bytes cumulative stack size)");
    std::vector<KernelResources> out;
    std::istringstream in(text);
    std::string line, props;  // props: the function whose properties the next lines give
    static const std::string kProps = "Function properties for ";
    while (std::getline(in, line)) {
        std::smatch m;
        if (std::regex_search(line, m, entry)) {
            out.push_back({});
            out.back().kernel = m[1];
            props.clear();
        } else if (const auto at = line.find(kProps); at != std::string::npos) {
            props = line.substr(at + kProps.size());
            while (!props.empty() && std::isspace(static_cast<unsigned char>(props.back()))) props.pop_back();
        } else if (out.empty() || props != out.back().kernel) {
            continue;  // a called function's properties, or a line before the first kernel
        } else if (std::regex_search(line, m, frame)) {
            out.back().stack_bytes = std::stoi(m[1]);
            out.back().spill_bytes = std::stoi(m[2]) + std::stoi(m[3]);
        } else if (std::regex_search(line, m, used)) {
            out.back().registers = std::stoi(m[1]);
            if (std::regex_search(line, m, cumulative)) out.back().stack_bytes = std::stoi(m[1]);
        }
    }
    return out;
}

std::vector<KernelResources> parse_amdgpu_metadata(const std::string& assembly) {
    const auto begin = assembly.find(".amdgpu_metadata");
    const auto end = assembly.find(".end_amdgpu_metadata", begin == std::string::npos ? 0 : begin);
    std::vector<KernelResources> out;
    if (begin == std::string::npos || end == std::string::npos) return out;
    // Kernel entries are "  - .args:" items; their own keys are indented by four spaces.
    static const std::regex key(R"(^    \.([a-z_]+):\s+(\S+)\s*$)");
    std::istringstream in(assembly.substr(begin, end - begin));
    std::string line;
    KernelResources k;
    bool open = false;
    auto close = [&] {
        if (open && !k.kernel.empty()) out.push_back(k);
        k = {};
    };
    while (std::getline(in, line)) {
        if (line.rfind("  - ", 0) == 0 && line.find(".args:") != std::string::npos) {
            close();
            open = true;
            continue;
        }
        if (line.rfind("amdhsa.", 0) == 0) {
            close();
            open = false;
            continue;
        }
        std::smatch m;
        if (!open || !std::regex_match(line, m, key)) continue;
        const std::string name = m[1], value = m[2];
        if (name == "name") k.kernel = value;
        else if (name == "vgpr_count") k.registers = std::stoi(value);
        else if (name == "sgpr_count") k.sgprs = std::stoi(value);
        else if (name == "private_segment_fixed_size") k.stack_bytes = std::stoi(value);
        else if (name == "vgpr_spill_count" || name == "sgpr_spill_count") k.spill_bytes += std::stoi(value);
    }
    close();
    return out;
}

std::vector<std::string> parse_undefined_symbols(const std::string& nm_output) {
    std::vector<std::string> out;
    std::istringstream in(nm_output);
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream words(line);
        std::string type, name;
        if (!(words >> type >> name) || type != "U") continue;
        if (name.rfind("llvm.", 0) == 0) continue;  // intrinsics: the back end lowers them
        out.push_back(name);
    }
    return out;
}

}  // namespace clpath
