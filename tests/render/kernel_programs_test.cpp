// The programs clpath builds (render/kernel_programs.hpp): the covering set
// the portability gate compiles is made by the functions a render uses, holds
// every feature switch the kernels test, and each program's options are what
// the renderer and the ray-batch benchmark pass to the device.
#include <gtest/gtest.h>

#include <cstdlib>
#include <map>
#include <regex>
#include <set>
#include <string>

#include "cl/embedded_sources.hpp"
#include "render/kernel_programs.hpp"
#include "render/settings.hpp"
#include "scene/load/scene_loader.hpp"
#include "util/error.hpp"

using namespace clpath;

namespace {

std::map<std::string, ProgramSpec> by_name(const std::vector<ProgramSpec>& programs) {
    std::map<std::string, ProgramSpec> m;
    for (const auto& p : programs) EXPECT_TRUE(m.emplace(p.name, p).second) << "two programs named " << p.name;
    return m;
}

bool has_define(const std::string& options, const std::string& name) {
    return std::regex_search(options, std::regex("(^| )-D" + name + "(=| |$)"));
}

}  // namespace

// CPU code walks 8-wide nodes, GPU code 4-wide ones, and CPU code flushes
// subnormals: the two programs differ by the GPU define, the node layout's
// and that option, nothing else.
TEST(KernelPrograms, CodesDifferByTheGpuDefineTheLayoutAndDenormalsOnly) {
    KernelFeatures f;
    f.materials[CLP_MAT_DIFFUSE] = true;
    const ProgramSpec cpu = integrator_program(f, KernelCode::Cpu), gpu = integrator_program(f, KernelCode::Gpu);
    EXPECT_EQ(cpu.options, build_options(f) + " -cl-denorms-are-zero -DCLP_NODES_BVH8");
    EXPECT_EQ(gpu.options, build_options(f) + " -DCLP_TARGET_GPU");
    EXPECT_EQ(wavefront_program(f, KernelCode::Cpu).options, build_options(f) + " -cl-denorms-are-zero -DCLP_NODES_BVH8");
    EXPECT_EQ(cpu.roots, renderer_kernel_files());
    EXPECT_FALSE(has_define(ray_batch_program(Accel::Bvh, KernelCode::Cpu).options, "CLP_TARGET_GPU"));
    EXPECT_TRUE(has_define(ray_batch_program(Accel::Flat, KernelCode::Gpu).options, "CLP_TARGET_GPU"));
    EXPECT_TRUE(has_define(ray_batch_program(Accel::Flat, KernelCode::Cpu).options, "CLP_ACCEL_FLAT"));
    EXPECT_TRUE(has_define(ray_batch_program(Accel::Bvh, KernelCode::Cpu).options, "CLP_NODES_BVH8"));
    EXPECT_FALSE(has_define(ray_batch_program(Accel::Bvh, KernelCode::Gpu).options, "CLP_NODES_BVH8"));
    // The flat structure has no wide nodes, and instanced scenes walk 4-wide ones on every device.
    EXPECT_FALSE(has_define(ray_batch_program(Accel::Flat, KernelCode::Cpu).options, "CLP_NODES_BVH8"));
    EXPECT_FALSE(has_define(ray_batch_program(Accel::Bvh, KernelCode::Cpu, true).options, "CLP_NODES_BVH8"));
    f.instances = true;
    EXPECT_FALSE(has_define(integrator_program(f, KernelCode::Cpu).options, "CLP_NODES_BVH8"));
    EXPECT_EQ(node_layout(KernelCode::Cpu, false), NodeLayout::Bvh8);
    EXPECT_EQ(node_layout(KernelCode::Cpu, true), NodeLayout::Bvh4);
    EXPECT_EQ(node_layout(KernelCode::Gpu, false), NodeLayout::Bvh4);
}

TEST(KernelPrograms, CodeFollowsTheDeviceUnlessTheEnvironmentChooses) {
    DeviceInfo gpu, cpu;
    gpu.is_gpu = true;
    cpu.is_cpu = true;
    const char* before = std::getenv("CLPATH_KERNEL_CODE");
    const std::string saved = before ? before : "";
    unsetenv("CLPATH_KERNEL_CODE");
    EXPECT_EQ(kernel_code(gpu), KernelCode::Gpu);
    EXPECT_EQ(kernel_code(cpu), KernelCode::Cpu);
    setenv("CLPATH_KERNEL_CODE", "gpu", 1);
    EXPECT_EQ(kernel_code(cpu), KernelCode::Gpu);
    setenv("CLPATH_KERNEL_CODE", "cpu", 1);
    EXPECT_EQ(kernel_code(gpu), KernelCode::Cpu);
    setenv("CLPATH_KERNEL_CODE", "fpga", 1);
    EXPECT_THROW(kernel_code(gpu), UsageError);
    if (before)
        setenv("CLPATH_KERNEL_CODE", saved.c_str(), 1);
    else
        unsetenv("CLPATH_KERNEL_CODE");
}

TEST(KernelPrograms, CoveringSetHasEveryIntegratorEveryFeatureAloneAndBothRayBatchPrograms) {
    const auto programs = by_name(covering_programs({}, KernelCode::Gpu));
    for (const auto& name : integrator_names()) {
        ASSERT_TRUE(programs.count(name + "-all")) << name;
        ASSERT_TRUE(programs.count(name + "-all-alpha")) << name;
        EXPECT_TRUE(has_define(programs.at(name + "-all-alpha").options, "CLP_HAS_ALPHA"));
        EXPECT_FALSE(has_define(programs.at(name + "-all").options, "CLP_HAS_ALPHA"));
    }
    for (const char* alone : {"path-only-diffuse", "path-only-mirror", "path-only-gltf", "path-diffuse-textures",
                              "path-diffuse-alpha", "path-diffuse-environment-map", "path-flat-all",
                              "path-uniform-diffuse", "path-bsdf-diffuse", "rays-bvh", "rays-flat"})
        EXPECT_TRUE(programs.count(alone)) << alone;
    // The wavefront of both light-transport integrators, with its own kernels.
    for (const char* wf : {"wf-path-diffuse", "wf-path-all", "wf-path-all-alpha", "wf-path-flat-all",
                           "wf-path-bsdf-diffuse", "wf-path-bsdf-all", "wf-path-bsdf-all-alpha"}) {
        ASSERT_TRUE(programs.count(wf)) << wf;
        EXPECT_EQ(programs.at(wf).roots, wavefront_kernel_files()) << wf;
        EXPECT_EQ(programs.at(wf).kernels.front(), "wf_camera") << wf;
    }
    EXPECT_TRUE(has_define(programs.at("wf-path-all").options, "CLP_HAS_MAT_GLTF"));
    EXPECT_FALSE(programs.count("wf-ao-all"));
    EXPECT_EQ(programs.at("path-only-mirror").options,
              "-cl-std=CL1.2 -DCLP_HAS_MAT_MIRROR -DCLP_INTEGRATOR=0u -DCLP_MAX_DEPTH=16u -DCLP_TARGET_GPU");
    for (const auto& [name, p] : programs) EXPECT_TRUE(has_define(p.options, "CLP_TARGET_GPU")) << name;
}

// Every feature a scene can hold is switched by the covering set's list: all
// of them on, as a scene would have them, gives the program that
// --all-features compiles (with alpha and the glTF layers, which follow the
// scene). A field added to SceneFeatures that all_features turns on and the
// list misses fails here.
TEST(KernelPrograms, EverySceneFeatureOnIsTheAllFeaturesProgram) {
    const auto programs = covering_programs({}, KernelCode::Cpu);
    const ProgramSpec* all = nullptr;
    const ProgramSpec* switched = nullptr;
    for (const auto& p : programs) {
        if (p.name == "path-all-layers") all = &p;
        if (p.covers.find("every scene feature") != std::string::npos) switched = &p;
    }
    ASSERT_TRUE(all && switched);
    EXPECT_EQ(switched->name, "path-all-layers") << switched->options << "\nwhere --all-features gives\n"
                                                 << all->options;
    EXPECT_TRUE(has_define(all->options, "CLP_HAS_CLEARCOAT") && has_define(all->options, "CLP_HAS_TRANSMISSION"));
    // ... and the plain all-features programs stay without the layers.
    for (const auto& p : programs)
        if (p.name == "path-all-alpha" || p.name == "wf-path-all") EXPECT_FALSE(has_define(p.options, "CLP_HAS_CLEARCOAT")) << p.name;
}

// Every CLP_HAS_* switch the kernels test is on in some program of the set and
// off in another, so both branches of each #ifdef are compiled.
TEST(KernelPrograms, EverySwitchTheKernelsTestIsCompiledOnAndOff) {
    std::set<std::string> switches;
    static const std::regex tested(R"((?:ifdef|ifndef|defined\()\s*\(?(CLP_(?:HAS|ACCEL|UNIFORM|TARGET)_[A-Z_0-9]+))");
    for (const auto& s : embedded_sources()) {
        const std::string text = s.text;
        for (std::sregex_iterator it(text.begin(), text.end(), tested), end; it != end; ++it)
            switches.insert((*it)[1]);
    }
    ASSERT_GE(switches.size(), 14u);
    const auto gpu = covering_programs({}, KernelCode::Gpu), cpu = covering_programs({}, KernelCode::Cpu);
    for (const auto& sw : switches) {
        int on = 0, off = 0;
        for (const auto* set : {&gpu, &cpu})
            for (const auto& p : *set) (has_define(p.options, sw) ? on : off)++;
        EXPECT_GT(on, 0) << sw << " is never compiled in";
        EXPECT_GT(off, 0) << sw << " is always compiled in";
    }
}

TEST(KernelPrograms, AScenesProgramIsTheOneItsRenderBuilds) {
    const Scene scene = load_scene("cornell");
    const RenderSettings settings = settings_from_scene(scene.render);
    const NamedSceneFeatures named{"cornell", scene_features(scene), settings};
    const auto programs = scene_programs(named, KernelCode::Gpu);
    ASSERT_EQ(programs.size(), 4u);
    const KernelFeatures features = kernel_features(scene_features(scene), settings);
    EXPECT_EQ(programs[0].name, "scene-cornell");
    EXPECT_EQ(programs[0].options, integrator_program(features, KernelCode::Gpu).options);
    EXPECT_EQ(programs[0].roots, renderer_kernel_files());
    // Cornell renders with the path integrator, which has a wavefront shape.
    EXPECT_EQ(programs[1].name, "wf-scene-cornell");
    EXPECT_EQ(programs[1].options, wavefront_program(features, KernelCode::Gpu).options);
    EXPECT_EQ(programs[1].roots, wavefront_kernel_files());
    EXPECT_EQ(programs[2].options, ray_batch_program(Accel::Bvh, KernelCode::Gpu).options);
    // In the covering set a scene's program that another entry already is
    // joins it: one megakernel and one wavefront entry name the scene.
    const auto all = covering_programs({named}, KernelCode::Gpu);
    int with_cornell = 0;
    for (const auto& p : all) with_cornell += p.covers.find("scene cornell") != std::string::npos;
    EXPECT_EQ(with_cornell, 2);
}

// bench instances walks the two levels: an instanced scene's batch program
// has the two-level walk, and the covering set compiles it (so its batch
// kernels are held to their budgets, render/kernel_report.cpp).
TEST(KernelPrograms, AnInstancedScenesBatchProgramWalksTwoLevels) {
    const Scene scene = load_scene("bunnies:2");
    const NamedSceneFeatures named{"bunnies", scene_features(scene), settings_from_scene(scene.render)};
    const auto programs = scene_programs(named, KernelCode::Gpu);
    ASSERT_EQ(programs.size(), 3u);
    EXPECT_EQ(programs[2].name, "rays-bvh-instances");
    EXPECT_TRUE(has_define(programs[2].options, "CLP_HAS_INSTANCES"));
    EXPECT_FALSE(has_define(ray_batch_program(Accel::Bvh, KernelCode::Gpu).options, "CLP_HAS_INSTANCES"));
    EXPECT_THROW(ray_batch_program(Accel::Flat, KernelCode::Gpu, true), Error);
    int covered = 0;
    for (const auto& p : covering_programs({}, KernelCode::Gpu))
        covered += p.name == "rays-bvh-instances" && has_define(p.options, "CLP_HAS_INSTANCES");
    EXPECT_EQ(covered, 1);
}
