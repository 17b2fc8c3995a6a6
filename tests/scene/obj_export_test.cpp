// clpath export: the OBJ + MTL + scene file it writes, read back through
// clpath's own loaders, are the same scene and render the same image; what
// another renderer would model differently is refused.
#include <gtest/gtest.h>

#include "scene/memory_files.hpp"
#include "scene/export/obj_export.hpp"
#include "scene/load/scene_loader.hpp"
#include "scene/shapes.hpp"
#include "support/image_agreement.hpp"
#include "support/render_helpers.hpp"

namespace clpath {
namespace {

Scene bundled(const std::string& name) { return load_scene(test::scenes_dir() + "/" + name + ".json"); }

Scene round_trip(const Scene& s, const std::string& stem) {
    const ObjExport e = export_obj_scene(s, stem, "test");
    test::MemoryFiles files;
    files.files["/mem/" + stem + ".json"] = e.json;
    files.files["/mem/" + stem + ".obj"] = e.obj;
    files.files["/mem/" + stem + ".mtl"] = e.mtl;
    return load_scene("/mem/" + stem + ".json", files.options());
}

std::vector<Image> runs(const Scene& scene, std::uint32_t seed0) {
    RenderSettings st;
    st.max_depth = 8;
    std::vector<Image> out;
    for (std::uint32_t i = 0; i < 4; ++i) {
        st.seed = seed0 + i;
        out.push_back(test::render(scene, st, 16).linear);
    }
    return out;
}

// One-sided emitters travel in the MTL (Ke), two-sided ones in the scene file:
// cornell-classic has the first, cornell-thesis-diffuse the second.
TEST(ObjExport, BundledDiffuseScenesRoundTrip) {
    for (const std::string name : {"cornell-classic", "cornell-thesis-diffuse"}) {
        SCOPED_TRACE(name);
        Scene a = bundled(name);
        a.camera.width = 32;
        a.camera.height = 24;
        const Scene b = round_trip(a, name);
        ASSERT_EQ(b.triangle_count(), a.triangle_count());
        EXPECT_EQ(b.vertices, a.vertices);  // %.9g reads back as the same float
        for (std::size_t t = 0; t < a.triangle_count(); ++t) {
            const Material &ma = a.materials[a.triangle_material[t]], &mb = b.materials[b.triangle_material[t]];
            ASSERT_EQ(mb.kind, ma.kind) << "triangle " << t;
            ASSERT_EQ(load3(mb.albedo), load3(ma.albedo)) << "triangle " << t;
            ASSERT_EQ(load3(mb.emission), load3(ma.emission)) << "triangle " << t;
            ASSERT_EQ(mb.flags, ma.flags) << "triangle " << t;
        }
        EXPECT_EQ(b.camera.eye, a.camera.eye);
        EXPECT_EQ(b.camera.target, a.camera.target);
        EXPECT_EQ(b.camera.vfov_degrees, a.camera.vfov_degrees);
        EXPECT_EQ(b.camera.width, 32);
        EXPECT_EQ(b.render.max_depth, a.render.max_depth);
        // Rendered with independent seeds on each side: equal in distribution.
        const auto r = test::image_agreement(runs(a, 10), runs(b, 20));
        EXPECT_TRUE(r.ok()) << r.describe();
    }
}

TEST(ObjExport, RefusesWhatCyclesModelsDifferently) {
    auto refused = [](const Scene& s, const std::string& what) {
        try {
            export_obj_scene(s, "x", "test");
            ADD_FAILURE() << "exported a scene with " << what;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
        }
    };
    refused(bundled("cornell-thesis"), "material 'glass' is a dielectric");
    Scene lit = bundled("cornell-classic");
    lit.lights.push_back(PunctualLight{});
    refused(lit, "punctual light");
    Scene smooth = bundled("cornell-classic");
    smooth.normals.assign(smooth.vertices.size(), glm::vec3(0, 1, 0));
    refused(smooth, "shading normals");
}

}  // namespace
}  // namespace clpath
