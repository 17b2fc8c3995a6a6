#include "render/kernel_programs.hpp"

#include <cstdlib>
#include <functional>
#include <map>
#include <utility>

#include "cl/embedded_sources.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

// Indexed by CLP_MAT_*, from the one table of kinds (kernels/shared_structs.h).
#define CLP_MAT_NAME(KIND, name, in_scene_files) #name,
const char* const kMaterialNames[CLP_MAT_KIND_COUNT] = {CLP_MATERIAL_KINDS(CLP_MAT_NAME)};
#undef CLP_MAT_NAME

// CPU programs flush subnormals (-cl-denorms-are-zero; Embree's tutorials set
// FTZ and DAZ on every thread likewise). A TriVerts row carries an integer in
// its fourth lane (the triangle's index: a subnormal float below 2^23) and the
// triangle test subtracts whole rows, so without it x86 met a subnormal
// operand in nearly every leaf test. The arithmetic needs none: the triangle
// test's products reach 2^-126 only at scene scales far below the 1e-4 the
// robustness suite renders, and a product flushed to zero is flushed alike in
// the two triangles sharing the edge (still watertight); the exact film
// converts its sums bit by bit (film.cl).
std::string code_options(KernelCode code) {
    return code == KernelCode::Gpu ? " -DCLP_TARGET_GPU" : " -cl-denorms-are-zero";
}

// The node layout's option, none for the flat structure (which has no wide nodes).
std::string walk_options(bool flat, KernelCode code, bool instances) {
    return flat ? "" : layout_options(node_layout(code, instances));
}

// A feature a scene can hold, by name, and how to switch it on.
struct SceneSwitch {
    const char* name;
    std::function<void(SceneFeatures&)> on;
};

// Every SceneFeatures field (scene_features() sets them; kernel_features()
// turns them into CLP_HAS_* switches). A field added there and missed here
// is caught by tests/render/kernel_programs_test.cpp, which checks that
// switching every feature on gives the all-features program.
const std::vector<SceneSwitch>& scene_switches() {
    static const std::vector<SceneSwitch> s = [] {
        std::vector<SceneSwitch> v;
        for (std::uint32_t k = 0; k < CLP_MAT_KIND_COUNT; ++k)
            v.push_back({kMaterialNames[k], [k](SceneFeatures& f) { f.materials[k] = true; }});
        v.push_back({"emission", [](SceneFeatures& f) { f.emission = true; }});
        v.push_back({"lights", [](SceneFeatures& f) { f.lights = true; }});
        v.push_back({"environment", [](SceneFeatures& f) { f.environment = true; }});
        v.push_back({"environment-map", [](SceneFeatures& f) { f.environment = f.environment_map = true; }});
        v.push_back({"normals", [](SceneFeatures& f) { f.normals = true; }});
        v.push_back({"textures", [](SceneFeatures& f) { f.textures = true; }});
        v.push_back({"vertex-colors", [](SceneFeatures& f) { f.vertex_colors = true; }});
        // With every attribute the coverage test may read.
        v.push_back({"alpha", [](SceneFeatures& f) {
                         f.alpha = true;
                         f.attributes = CLP_SCENE_ATTRIBUTES;
                     }});
        // The glTF layers exist only on glTF materials.
        v.push_back({"clearcoat", [](SceneFeatures& f) { f.materials[CLP_MAT_GLTF] = f.clearcoat = true; }});
        v.push_back({"transmission", [](SceneFeatures& f) { f.materials[CLP_MAT_GLTF] = f.transmission = true; }});
        // Many emitters: the light BVH picks them (LightSampler::Auto).
        v.push_back({"many-lights", [](SceneFeatures& f) { f.emission = f.many_lights = true; }});
        return v;
    }();
    return s;
}

SceneFeatures every_scene_feature() {
    SceneFeatures f;
    for (const auto& s : scene_switches()) s.on(f);
    return f;
}

SceneFeatures diffuse_only() {
    SceneFeatures f;
    f.materials[CLP_MAT_DIFFUSE] = true;
    return f;
}

// Programs in order, merged by (roots, options).
class ProgramList {
public:
    explicit ProgramList(KernelCode code) : code_(code) {}

    void add(ProgramSpec p, const std::string& covers) {
        std::string key;
        for (const auto& r : p.roots) key += r + "\n";
        key += p.options;
        auto it = index_.find(key);
        if (it != index_.end()) {
            std::string& c = list_[it->second].covers;
            c += (c.empty() ? "" : "; ") + covers;
            return;
        }
        p.covers = covers;
        index_.emplace(key, list_.size());
        list_.push_back(std::move(p));
    }
    // The integrator program of a scene with these features rendered with these settings.
    void add_render(const std::string& name, const SceneFeatures& scene, const RenderSettings& settings,
                    const std::string& covers) {
        ProgramSpec p = integrator_program(kernel_features(scene, settings), code_);
        p.name = name;
        add(std::move(p), covers);
    }
    // The same scene's wavefront program (wavefront.cl).
    void add_wavefront(const std::string& name, const SceneFeatures& scene, const RenderSettings& settings,
                       const std::string& covers) {
        ProgramSpec p = wavefront_program(kernel_features(scene, settings), code_);
        p.name = "wf-" + name;
        add(std::move(p), covers);
    }
    std::vector<ProgramSpec> take() { return std::move(list_); }

private:
    KernelCode code_;
    std::vector<ProgramSpec> list_;
    std::map<std::string, std::size_t> index_;
};

}  // namespace

KernelCode kernel_code(const DeviceInfo& device) {
    if (const char* forced = std::getenv("CLPATH_KERNEL_CODE"); forced && *forced) {
        try {
            return parse_kernel_code(forced);
        } catch (const UsageError&) {
            throw UsageError(std::string("CLPATH_KERNEL_CODE=") + forced + ": choose gpu or cpu");
        }
    }
    return device.is_gpu ? KernelCode::Gpu : KernelCode::Cpu;
}

const char* kernel_code_name(KernelCode code) { return code == KernelCode::Gpu ? "gpu" : "cpu"; }

NodeLayout node_layout(KernelCode code, bool instances) {
    return code == KernelCode::Cpu && !instances ? NodeLayout::Bvh8 : NodeLayout::Bvh4;
}

std::string layout_options(NodeLayout layout) { return layout == NodeLayout::Bvh8 ? " -DCLP_NODES_BVH8" : ""; }

KernelCode parse_kernel_code(const std::string& name) {
    if (name == "gpu") return KernelCode::Gpu;
    if (name == "cpu") return KernelCode::Cpu;
    throw UsageError("unknown kernel code '" + name + "' (choose gpu or cpu)");
}

ProgramSpec integrator_program(const KernelFeatures& features, KernelCode code) {
    ProgramSpec p;
    p.name = std::string(integrator_name(features.integrator));
    p.roots = renderer_kernel_files();
    p.options = build_options(features) + code_options(code) + walk_options(features.flat_accel, code, features.instances);
    p.kernels = {"render_paths", "film_resolve", "film_add_exact", "film_add_exact_half"};
    return p;
}

ProgramSpec wavefront_program(const KernelFeatures& features, KernelCode code) {
    ProgramSpec p;
    p.name = std::string("wf-") + integrator_name(features.integrator);
    p.roots = wavefront_kernel_files();
    p.options = build_options(features) + code_options(code) + walk_options(features.flat_accel, code, features.instances);
    p.kernels = {"wf_camera",      "wf_trace",      "wf_shade",     "wf_light",       "wf_connect",
                 "wf_scatter",     "wf_shadow",     "wf_next_bounce", "wf_accumulate", "film_resolve",
                 "film_add_exact", "film_add_exact_half"};
    return p;
}

bool has_wavefront(std::uint32_t integrator) {
    return integrator == CLP_INTEGRATOR_PATH || integrator == CLP_INTEGRATOR_PATH_BSDF;
}

ProgramSpec ray_batch_program(Accel accel, KernelCode code, bool instances) {
    if (instances && accel != Accel::Bvh) throw Error("internal: instances are walked in the BVH only");
    ProgramSpec p;
    p.name = std::string("rays-") + accel_name(accel) + (instances ? "-instances" : "");
    p.roots = {"ray_batches.cl"};
    p.options = std::string(accel == Accel::Flat ? "-cl-std=CL1.2 -DCLP_ACCEL_FLAT" : "-cl-std=CL1.2") +
                (instances ? " -DCLP_HAS_INSTANCES" : "") + code_options(code) +
                walk_options(accel == Accel::Flat, code, instances);
    p.kernels = {"batch_primary_rays", "batch_secondary_rays", "batch_trace_closest", "batch_trace_any"};
    return p;
}

std::vector<ProgramSpec> scene_programs(const NamedSceneFeatures& scene, KernelCode code) {
    ProgramList list(code);
    list.add_render("scene-" + scene.name, scene.features, scene.settings, "scene " + scene.name);
    if (has_wavefront(scene.settings.integrator))
        list.add_wavefront("scene-" + scene.name, scene.features, scene.settings, "scene " + scene.name + ", wavefront");
    if (scene.features.instances)
        list.add(ray_batch_program(Accel::Bvh, code, true), "bench instances " + scene.name);
    else
        for (Accel a : {Accel::Bvh, Accel::Flat}) list.add(ray_batch_program(a, code), "bench rays " + scene.name);
    return list.take();
}

std::vector<ProgramSpec> covering_programs(const std::vector<NamedSceneFeatures>& scenes, KernelCode code) {
    ProgramList list(code);
    const RenderSettings defaults;
    // The glTF layers, as alpha, follow the scene even with every feature
    // compiled in (render/kernel_features.hpp): programs with them and without.
    const SceneFeatures all_layers = every_scene_feature();
    SceneFeatures all = all_layers;
    all.clearcoat = all.transmission = false;
    SceneFeatures all_opaque = all;
    all_opaque.alpha = false;

    // Every integrator with everything compiled in, alpha off and on.
    for (std::uint32_t i = 0; i < CLP_INTEGRATOR_COUNT; ++i) {
        RenderSettings s = defaults;
        s.integrator = i;
        s.all_features = true;
        const std::string n = integrator_name(i);
        list.add_render(n + "-all", all_opaque, s, n + " integrator, every feature");
        list.add_render(n + "-all-alpha", all, s, n + " integrator, every feature and alpha");
    }
    {
        RenderSettings s = defaults;
        s.all_features = true;
        list.add_render("path-all-layers", all_layers, s, "path integrator, every feature, alpha and the glTF layers");
    }
    // Each feature alone (over diffuse, which every scene but a one-material one has),
    // and each material kind alone.
    const auto& switches = scene_switches();
    for (std::size_t k = 0; k < switches.size(); ++k) {
        const SceneSwitch& sw = switches[k];
        const std::string name = sw.name;
        SceneFeatures one = diffuse_only();
        sw.on(one);
        if (k != CLP_MAT_DIFFUSE) list.add_render("path-diffuse-" + name, one, defaults, "diffuse and " + name);
        if (k < CLP_MAT_KIND_COUNT) {  // the first switches are the material kinds
            SceneFeatures kind;
            sw.on(kind);
            list.add_render("path-only-" + name, kind, defaults, name + " alone");
        }
    }
    // Every feature a scene can hold, switched on as a scene would: the
    // program --all-features compiles (tests/render/kernel_programs_test.cpp).
    list.add_render("path-every-scene-feature", all_layers, defaults, "every scene feature");
    // The estimator and structure choices that are compiled in.
    for (const bool everything : {false, true}) {
        const SceneFeatures f = everything ? all_opaque : diffuse_only();
        const std::string what = everything ? "all" : "diffuse";
        RenderSettings flat = defaults;
        flat.accel = Accel::Flat;
        list.add_render("path-flat-" + what, f, flat, "flat object list, " + what);
        RenderSettings uniform = defaults;
        uniform.hemisphere = kHemisphereUniform;
        list.add_render("path-uniform-" + what, f, uniform, "uniform hemisphere, " + what);
        RenderSettings bsdf = defaults;
        bsdf.integrator = CLP_INTEGRATOR_PATH_BSDF;
        list.add_render("path-bsdf-" + what, f, bsdf, "BSDF sampling only, " + what);
    }
    // Both light samplers with every feature: the programs above pick by the
    // light BVH where the features include many lights, so the alias table's
    // pick is added here, and the light BVH's in the wavefront shape below.
    {
        RenderSettings power = defaults;
        power.all_features = true;
        power.light_sampler = LightSampler::Power;
        list.add_render("path-all-power", all_opaque, power, "path integrator, every feature, lights picked by power");
        list.add_wavefront("path-all-power", all_opaque, power, "wavefront path, every feature, lights picked by power");
    }
    // The wavefront shape of both light-transport integrators: its kernels
    // include the megakernel's path and scene code (path.cl, scene_data.cl)
    // whose switches the programs above cover pairwise, so every feature on
    // (alpha off and on) and diffuse alone, with each structure.
    for (const std::uint32_t i : {CLP_INTEGRATOR_PATH, CLP_INTEGRATOR_PATH_BSDF}) {
        RenderSettings s = defaults;
        s.integrator = i;
        const std::string n = integrator_name(i);
        list.add_wavefront(n + "-diffuse", diffuse_only(), s, "wavefront " + n + ", diffuse");
        s.all_features = true;
        list.add_wavefront(n + "-all", all_opaque, s, "wavefront " + n + ", every feature");
        list.add_wavefront(n + "-all-alpha", all, s, "wavefront " + n + ", every feature and alpha");
        list.add_wavefront(n + "-all-layers", all_layers, s, "wavefront " + n + ", every feature, alpha and the glTF layers");
        s.accel = Accel::Flat;
        list.add_wavefront(n + "-flat-all", all_opaque, s, "wavefront " + n + ", flat object list, every feature");
    }
    // Instances change the walk and the surface (the two-level BVH,
    // CLP_HAS_INSTANCES): over diffuse, and with every feature (an instanced
    // mesh's tangent frames move with it: surface_params.cl), in both
    // shapes. Not a scene switch of the programs above: it follows the scene
    // even with every feature compiled in (the node buffer's layout), and the
    // flat list has none.
    {
        SceneFeatures inst = diffuse_only();
        inst.instances = true;
        list.add_render("path-diffuse-instances", inst, defaults, "diffuse, meshes placed by instances");
        list.add_wavefront("path-diffuse-instances", inst, defaults, "wavefront path, diffuse, instances");
        SceneFeatures inst_all = all_layers;
        inst_all.instances = true;
        RenderSettings s = defaults;
        s.all_features = true;
        list.add_render("path-all-instances", inst_all, s, "every feature, the glTF layers and instances");
        list.add_wavefront("path-all-instances", inst_all, s, "wavefront path, every feature, the glTF layers and instances");
    }
    for (Accel a : {Accel::Bvh, Accel::Flat}) list.add(ray_batch_program(a, code), "bench rays");
    list.add(ray_batch_program(Accel::Bvh, code, true), "bench instances");
    for (const auto& sc : scenes)
        for (auto& p : scene_programs(sc, code)) {
            const std::string covers = p.covers;
            list.add(std::move(p), covers);
        }
    return list.take();
}

}  // namespace clpath
