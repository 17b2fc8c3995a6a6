// The material kinds' table (CLP_MATERIAL_KINDS, kernels/shared_structs.h) is
// the one list of kinds: every kind in it must be named, switched on in the
// kernels' build options, handled by the kernels' three material switches
// (sample, evaluate, is-delta), read from scene files where the table says
// so, and known to both exporters. Each check runs over the table, so a kind
// added to it and missed anywhere fails here; a control shows the kernel
// check rejects a kind the kernels do not handle.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <set>
#include <string>

#include "kernels/bsdf_checks.hpp"
#include "render/kernel_features.hpp"
#include "scene/export/mitsuba_export.hpp"
#include "scene/export/obj_export.hpp"
#include "scene/load/scene_file.hpp"
#include "scene/scene.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

// A material of the kind with middling parameters: rough enough to have a
// lobe, not so rough that it is diffuse.
Material generic(std::uint32_t kind) {
    Material m = base_material();
    m.kind = kind;
    for (int i = 0; i < 3; ++i) m.albedo[i] = 0.8f;
    m.roughness = 0.5f;
    m.ior = 1.5f;
    return m;
}

int is_delta(const Material& m) {
    Buffer mb = test::upload(std::vector<Material>{m}, "material");
    Buffer out = test::device().buffer(sizeof(cl_int), CL_MEM_READ_WRITE, "is delta");
    Kernel k = test::device().kernel(test::probe_program(), "probe_bsdf_is_delta");
    k.arg(0, mb).arg(1, out);
    test::run(k, 1);
    return test::download<cl_int>(out, 1)[0];
}

// Empty when the kernels handle the material consistently: sampling scatters
// some light; a delta sample comes with is_delta and evaluates to zero; a
// non-delta sample's value and pdf are what evaluation gives for its
// direction. Otherwise, what is wrong.
std::string kernel_handling(const Material& m) {
    const glm::vec3 wo = test::bsdf::from_angle(30);
    const std::uint32_t n = 2048;
    const test::bsdf::Samples s = test::bsdf::sample(m, wo, n);
    std::vector<cl_float4> wos, wis, weights;
    int scattered = 0, delta = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
        if (s.wi_pdf[i].s[3] < 0) continue;
        const cl_float4 w = s.weight[i];
        if (!(w.s[0] + w.s[1] + w.s[2] > 0)) continue;
        ++scattered;
        if (w.s[3] != 0) {
            ++delta;
        } else {
            wos.push_back(test::bsdf::f4(wo));
            wis.push_back(s.wi_pdf[i]);
            weights.push_back(w);
        }
    }
    if (scattered == 0) return "material_sample scatters nothing";
    if (is_delta(m) != (delta > 0))
        return "material_is_delta says " + std::to_string(is_delta(m)) + ", material_sample gave " +
               std::to_string(delta) + " delta samples";
    if (wis.empty()) return "";
    const std::vector<cl_float4> ev = test::bsdf::eval(m, wos, wis);
    for (std::size_t i = 0; i < ev.size(); ++i) {
        const double pdf = wis[i].s[3], eval_pdf = ev[i].s[3];
        if (!(std::abs(eval_pdf - pdf) <= 1e-3 * pdf))
            return "material_eval's pdf " + std::to_string(eval_pdf) + " is not the sampled " + std::to_string(pdf);
        for (int c = 0; c < 3; ++c) {
            const double f = ev[i].s[c], expect = weights[i].s[c] * pdf;
            if (!(std::abs(f - expect) <= 1e-3 * expect + 1e-7))
                return "material_eval's value " + std::to_string(f) + " is not weight x pdf " + std::to_string(expect);
        }
    }
    return "";
}

std::string upper(std::string s) {
    for (char& c : s) c = char(std::toupper(static_cast<unsigned char>(c)));
    return s;
}

// One triangle of the kind, lit by an emitter, as the exporters take it.
Scene one_triangle(std::uint32_t kind) {
    Scene s;
    SceneMaterial m = base_material();
    static_cast<Material&>(m) = generic(kind);
    const std::uint32_t mat = s.add_material("surface", m);
    s.add_triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, mat);
    s.add_triangles({{0, 0, 2}, {0, 1, 2}, {1, 0, 2}}, s.add_material("lamp", emitter(glm::vec3(1))));
    s.camera.eye = {0.3f, 0.3f, 3};
    s.camera.target = {0.3f, 0.3f, 0};
    s.camera.width = s.camera.height = 8;
    return s;
}

TEST(MaterialKinds, EveryKindIsNamedOnceAndSwitchedInTheKernels) {
    std::set<std::string> names;
    for (std::uint32_t k = 0; k < CLP_MAT_KIND_COUNT; ++k) {
        const std::string name = material_kind_name(k);
        EXPECT_FALSE(name.empty()) << k;
        EXPECT_TRUE(names.insert(name).second) << name << " is named twice";
        KernelFeatures f;
        f.materials[k] = true;
        const std::string options = build_options(f) + " ";
        EXPECT_NE(options.find(" -DCLP_HAS_MAT_" + upper(name) + " "), std::string::npos) << options;
    }
    EXPECT_THROW(material_kind_name(CLP_MAT_KIND_COUNT), Error);
}

TEST(MaterialKinds, TheKernelsHandleEveryKind) {
    for (std::uint32_t k = 0; k < CLP_MAT_KIND_COUNT; ++k) {
        SCOPED_TRACE(material_kind_name(k));
        EXPECT_EQ(kernel_handling(generic(k)), "");
    }
}

TEST(MaterialKinds, ControlAKindTheKernelsLackIsCaught) {
    EXPECT_EQ(kernel_handling(generic(CLP_MAT_KIND_COUNT)), "material_sample scatters nothing");
}

TEST(MaterialKinds, SceneFilesNameTheKindsTheTableSays) {
    for (std::uint32_t k = 0; k < CLP_MAT_KIND_COUNT; ++k) {
        const std::string name = material_kind_name(k);
        const std::string text = std::string(R"({"camera": {"eye": [0, 0, -3], "target": [0, 0, 0]}, "materials": )") +
                                 R"({"m": {"type": ")" + name + R"("}, "lamp": {"type": "emitter", "emission": 1}},)" +
                                 R"( "objects": [{"type": "plane", "material": "m"}]})";
        if (material_kind_in_scene_files(k)) {
            const Scene s = parse_scene_file(text, "kinds.json");
            ASSERT_FALSE(s.materials.empty()) << name;
            EXPECT_EQ(s.materials.front().kind, k) << name;
        } else {
            EXPECT_THROW(parse_scene_file(text, "kinds.json"), Error) << name;
        }
    }
}

TEST(MaterialKinds, BothExportersKnowEveryKind) {
    for (std::uint32_t k = 0; k < CLP_MAT_KIND_COUNT; ++k) {
        const std::string name = material_kind_name(k);
        const Scene s = one_triangle(k);
        try {
            export_mitsuba_scene(s, "kinds", "kinds.json");
        } catch (const Error& e) {
            ADD_FAILURE() << name << ": the Mitsuba export failed: " << e.what();
        }
        try {
            export_obj_scene(s, "kinds", "kinds.json");
            EXPECT_EQ(k, CLP_MAT_DIFFUSE) << name << " was exported to OBJ, which models diffuse surfaces only";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("material 'surface' is a " + name + ":"), std::string::npos)
                << e.what();
        }
    }
}

}  // namespace
}  // namespace clpath
