#pragma once
// The OpenCL programs clpath builds, each as the root kernel files and the
// build options it is compiled from, and the set of them that covers every
// program a scene can select. The renderer (integrator_program.cpp) and the
// ray-batch benchmark build their programs from these specs, and
// `clpath kernels` dumps and compiles the same specs for GPU targets, so the
// portability gate checks what clpath really builds.
#include <string>
#include <vector>

#include "bvh/accel.hpp"
#include "cl/device.hpp"
#include "render/kernel_features.hpp"

namespace clpath {

// Which code of the kernels a device gets (whatever its integrator shape,
// megakernel or wavefront: settings.hpp). GPU programs are built with
// -DCLP_TARGET_GPU, which selects the code paths shaped for GPUs (fewer
// registers, no indexed private arrays outside the traversal stack); CPUs
// keep the paths measured fastest on PoCL. Both compute the same answers.
enum class KernelCode { Cpu, Gpu };
// Gpu for OpenCL GPU devices, else Cpu; CLPATH_KERNEL_CODE=gpu|cpu chooses
// for every device (the tests run each code on PoCL and on Oclgrind).
KernelCode kernel_code(const DeviceInfo& device);
const char* kernel_code_name(KernelCode code);    // "cpu", "gpu"
KernelCode parse_kernel_code(const std::string& name);  // throws clpath::UsageError

// The BVH node layout a program walks (bvh/accel.hpp): eight children per
// node for CPU code, four for GPU code (its register and stack budgets were
// measured on the 4-wide walk) and for instanced scenes (the two-level walk
// is 4-wide). The node buffer (device_nodes) and the program's
// layout_options must come from the same choice; every program spec below
// takes it from here.
NodeLayout node_layout(KernelCode code, bool instances);
// " -DCLP_NODES_BVH8" for Bvh8, "" for Bvh4 (kernels/traverse.cl).
std::string layout_options(NodeLayout layout);

// One program: what clBuildProgram receives is program_source(roots) and options.
struct ProgramSpec {
    std::string name;                  // unique within a list, usable as a file name
    std::vector<std::string> roots;    // root kernel files (host/cl/embedded_sources.hpp)
    std::string options;               // build options, exactly as clpath passes them
    std::vector<std::string> kernels;  // the kernels the host creates from it
    std::string covers;                // what selects it (scenes, feature sets), for reports
};

// The renderer's program for these features (render_paths, film_resolve, film_add_exact, film_add_exact_half).
ProgramSpec integrator_program(const KernelFeatures& features, KernelCode code);
// The wavefront integrator's program for these features (wavefront.cl: wf_*,
// film_resolve, film_add_exact, film_add_exact_half), for the integrators that have one.
ProgramSpec wavefront_program(const KernelFeatures& features, KernelCode code);
bool has_wavefront(std::uint32_t integrator);
// The ray-batch benchmarks' program (clpath bench rays; with instances, the
// two-level walk of bench instances, -DCLP_HAS_INSTANCES).
ProgramSpec ray_batch_program(Accel accel, KernelCode code, bool instances = false);

// A scene's features under a name, for covering_programs.
struct NamedSceneFeatures {
    std::string name;
    SceneFeatures features;
    RenderSettings settings;  // the scene's own render settings
};

// The programs of one scene rendered with its settings (the megakernel, and the
// wavefront where its integrator has one), and benchmarked with bench rays
// (both structures), or, for a scene with instances, bench instances.
std::vector<ProgramSpec> scene_programs(const NamedSceneFeatures& scene, KernelCode code);

// A set of programs that covers every program a scene can select, with the
// scenes' own programs added (duplicates by source and options merged, their
// `covers` joined). 2^15 feature combinations times 7 integrators cannot all
// be compiled, and need not be: the kernels select code by #ifdef on one
// switch, or on two joined by || or && (textures or vertex colours; surface
// parameters or alpha; the path integrator and triangle lights), never more.
// So every pair of switches has to be compiled in each of its four states:
// both on is every integrator with every feature (alpha on and off: alpha
// changes traversal's arguments); one on and the other off is each feature
// alone over the material every scene has (diffuse) and each material kind
// alone; both off is diffuse alone. The flat structure, uniform hemisphere
// and BSDF-only sampling are compiled with every feature and with diffuse
// alone, and both ray-batch programs are added. Every program is made by
// kernel_features() and build_options(), the functions a render uses, from
// SceneFeatures and RenderSettings; a new #if on three switches needs a
// program here.
std::vector<ProgramSpec> covering_programs(const std::vector<NamedSceneFeatures>& scenes, KernelCode code);

}  // namespace clpath
