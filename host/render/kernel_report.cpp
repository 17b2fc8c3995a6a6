#include "render/kernel_report.hpp"

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>
#include <thread>

#include "cl/embedded_sources.hpp"
#include "util/error.hpp"

namespace clpath {
namespace fs = std::filesystem;
namespace {

void write_text(const fs::path& p, const std::string& text) {
    std::ofstream out(p, std::ios::binary);
    out << text;
    if (!out) throw Error("cannot write " + p.string());
}

std::string join(const std::vector<std::string>& v, const char* sep) {
    std::string s;
    for (const auto& x : v) s += (s.empty() ? "" : sep) + x;
    return s;
}

std::string csv_field(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

}  // namespace

void write_program_dump(const std::vector<ProgramSpec>& programs, const std::string& dir,
                        const KernelVariant& variant) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir)) throw Error(dir + ": cannot create the folder (" + ec.message() + ")");
    std::string index = "# name\tkernels\toptions\tselected by\n";
    for (const auto& p : programs) {
        const std::string options = variant_options(p.options, variant);
        write_text(fs::path(dir) / (p.name + ".cl"), variant_source(p.roots, variant));
        write_text(fs::path(dir) / (p.name + ".options"), options + "\n");
        index += p.name + "\t" + join(p.kernels, ",") + "\t" + options + "\t" + p.covers + "\n";
    }
    write_text(fs::path(dir) / "programs.tsv", index);
}

std::vector<ProgramCompile> compile_programs(const std::vector<ProgramSpec>& programs,
                                             const std::vector<std::string>& targets,
                                             const OfflineToolchain& tools, const CompileRun& run) {
    std::vector<std::string> usable;
    for (const auto& t : targets)
        if (missing_tools(tools, t).empty()) usable.push_back(t);
    std::vector<ProgramCompile> out(programs.size() * usable.size());
    std::vector<std::string> sources(programs.size());
    std::vector<std::string> options(programs.size());
    for (std::size_t i = 0; i < programs.size(); ++i) {
        sources[i] = variant_source(programs[i].roots, run.variant);
        options[i] = variant_options(programs[i].options, run.variant);
    }
    std::atomic<std::size_t> next{0};
    std::mutex report;
    std::exception_ptr failure;
    auto worker = [&] {
        for (;;) {
            const std::size_t k = next++;
            if (k >= out.size()) return;
            const std::size_t pi = k / usable.size();
            const std::string& target = usable[k % usable.size()];
            try {
                const std::string work = (fs::path(run.work_dir) / (programs[pi].name + "-" + target)).string();
                out[k].program = &programs[pi];
                out[k].result = compile_offline(tools, target, sources[pi], options[pi], work, run.cache_dir);
                std::lock_guard<std::mutex> lock(report);
                if (run.on_done) run.on_done(out[k]);
            } catch (...) {
                std::lock_guard<std::mutex> lock(report);
                if (!failure) failure = std::current_exception();
                next = out.size();
            }
        }
    };
    std::vector<std::thread> threads;
    for (int j = 0; j < std::max(1, run.jobs); ++j) threads.emplace_back(worker);
    for (auto& t : threads) t.join();
    if (failure) std::rethrow_exception(failure);
    return out;
}

namespace {

bool has_option(const std::string& options, const std::string& option) {
    return (" " + options + " ").find(" " + option + " ") != std::string::npos;
}

// Every option of a space-separated list is among the program's.
bool has_options(const std::string& options, const std::string& list) {
    std::istringstream in(list);
    std::string o;
    while (in >> o)
        if (!has_option(options, o)) return false;
    return true;
}

// Whether budget b applies to a program built with these options: its
// options present and its excluded one absent.
bool applies(const KernelBudget& b, const std::string& options) {
    return (!b.with_option || has_options(options, b.with_option)) &&
           (!b.without_option || !has_option(options, b.without_option));
}

}  // namespace

const std::vector<KernelBudget>& kernel_budgets() {
    static const std::vector<KernelBudget> b = {
        {"batch_trace_closest", "sm_90", 64, 256, nullptr, nullptr},
        {"batch_trace_any", "sm_90", 64, 256, nullptr, nullptr},
        // The wavefront's kernels are held to the traversal kernels' budget,
        // but for the shading kernels of glTF materials (textures, two GGX
        // lobes), which may take half as many registers again.
        {"wf_camera", "sm_90", 64, 256, nullptr, nullptr},
        {"wf_trace", "sm_90", 64, 256, nullptr, nullptr},
        {"wf_shade", "sm_90", 64, 256, nullptr, "-DCLP_HAS_MAT_GLTF"},
        {"wf_shade", "sm_90", 96, 256, "-DCLP_HAS_MAT_GLTF", nullptr},
        {"wf_light", "sm_90", 64, 256, nullptr, nullptr},
        {"wf_connect", "sm_90", 64, 256, nullptr, "-DCLP_HAS_MAT_GLTF"},
        {"wf_connect", "sm_90", 96, 256, "-DCLP_HAS_MAT_GLTF", nullptr},
        {"wf_scatter", "sm_90", 64, 256, nullptr, "-DCLP_HAS_MAT_GLTF"},
        {"wf_scatter", "sm_90", 96, 256, "-DCLP_HAS_MAT_GLTF", nullptr},
        {"wf_shadow", "sm_90", 64, 256, nullptr, nullptr},
        // Alpha cut-outs tested inside the two-level walk (instances): the
        // any-hit test's scene pointers beside the world and object rays.
        // Held at the figures the covering program first showed
        // (wf-path-all-instances, every feature); each alone fits.
        {"wf_trace", "sm_90", 64, 256, "-DCLP_HAS_ALPHA -DCLP_HAS_INSTANCES", nullptr, 72, 0},
        {"wf_shadow", "sm_90", 64, 256, "-DCLP_HAS_ALPHA -DCLP_HAS_INSTANCES", nullptr, 70, 0},
        {"wf_next_bounce", "sm_90", 64, 256, nullptr, nullptr},
        {"wf_accumulate", "sm_90", 64, 256, nullptr, nullptr},
    };
    return b;
}

namespace {

// Lines for kernels over budget: beyond what they are held at (open = false),
// or over the budget but within that (open = true).
std::vector<std::string> over_budget(const std::vector<ProgramCompile>& compiles, bool open) {
    std::vector<std::string> v;
    for (const auto& c : compiles) {
        if (!c.result.ok || c.program->options.find("-DCLP_TARGET_GPU") == std::string::npos) continue;
        for (const auto& k : c.result.kernels) {
            // The entries naming options the program has take the place of
            // those for any program (a held combination of features).
            bool specific = false;
            for (const auto& b : kernel_budgets())
                specific = specific || (k.kernel == b.kernel && c.result.target == b.target && b.with_option &&
                                        applies(b, c.program->options));
            for (const auto& b : kernel_budgets()) {
                if (k.kernel != b.kernel || c.result.target != b.target) continue;
                if (!applies(b, c.program->options) || (specific && !b.with_option)) continue;
                const std::string at = c.program->name + " " + k.kernel + " " + c.result.target + ": ";
                const int held_regs = std::max(b.max_registers, b.held_registers);
                const int held_stack = std::max(b.max_stack_bytes, b.held_stack_bytes);
                if (k.registers > b.max_registers && (k.registers > held_regs) != open)
                    v.push_back(at + std::to_string(k.registers) + " registers > " + std::to_string(b.max_registers) +
                                (open ? " (held at " + std::to_string(held_regs) + ")" : ""));
                if (k.stack_bytes > b.max_stack_bytes && (k.stack_bytes > held_stack) != open)
                    v.push_back(at + std::to_string(k.stack_bytes) + " B stack > " +
                                std::to_string(b.max_stack_bytes) +
                                (open ? " (held at " + std::to_string(held_stack) + ")" : ""));
                if (k.spill_bytes > 0 && !open) v.push_back(at + "spills (" + std::to_string(k.spill_bytes) + ")");
            }
        }
    }
    return v;
}

}  // namespace

std::vector<std::string> budget_violations(const std::vector<ProgramCompile>& compiles) {
    return over_budget(compiles, false);
}

std::vector<std::string> budget_shortfalls(const std::vector<ProgramCompile>& compiles) {
    return over_budget(compiles, true);
}

std::string resources_csv(const std::vector<ProgramCompile>& compiles) {
    std::ostringstream o;
    o << "program,kernel,target,registers,sgprs,stack_bytes,spills,options,selected_by\n";
    for (const auto& c : compiles) {
        const std::string tail = csv_field(c.program->options) + "," + csv_field(c.program->covers) + "\n";
        if (!c.result.ok) {
            o << csv_field(c.program->name) << ",FAILED," << c.result.target << ",,,,," << tail;
            continue;
        }
        for (const auto& k : c.result.kernels)
            o << csv_field(c.program->name) << "," << k.kernel << "," << c.result.target << "," << k.registers
              << "," << k.sgprs << "," << k.stack_bytes << "," << k.spill_bytes << "," << tail;
    }
    return o.str();
}

std::string resources_markdown(const std::vector<ProgramCompile>& compiles) {
    std::ostringstream o;
    o << "| program | kernel | target | registers | stack / private B | spills |\n|---|---|---|--:|--:|--:|\n";
    for (const auto& c : compiles) {
        if (!c.result.ok) {
            o << "| " << c.program->name << " | | " << c.result.target << " | **failed** | | |\n";
            continue;
        }
        for (const auto& k : c.result.kernels) {
            o << "| " << c.program->name << " | " << k.kernel << " | " << c.result.target << " | " << k.registers;
            if (k.sgprs) o << " (+" << k.sgprs << " SGPRs)";
            o << " | " << k.stack_bytes << " | " << k.spill_bytes << " |\n";
        }
    }
    return o.str();
}

}  // namespace clpath
