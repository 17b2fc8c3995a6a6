// A compressed glTF file renders the image its uncompressed original
// renders, bit for bit, through the real kernels: meshopt's lossless codecs
// give back the same floats, and Draco's quantisation is exact for geometry
// on its grid (whole-number positions over a range of 2^11 - 1 with 11 bits:
// a step of exactly 1). The control: with 8 bits the same file renders
// differently, so the comparison sees a change of geometry.
#include <gtest/gtest.h>

#include "scene/gltf_compressed_files.hpp"
#include "support/render_helpers.hpp"

using namespace clpath;
using namespace clpath::test;

namespace {

Image render_file(const std::string& name, const std::string& text) {
    Scene s = gltf_text_scene(name, text);
    s.camera.width = 24;
    s.camera.height = 16;
    RenderSettings settings;
    settings.seed = 11;
    settings.max_depth = 3;
    return test::render(s, settings, 4).linear;
}

}  // namespace

TEST(GltfCompressedRender, CompressedFilesRenderAsTheirOriginal) {
    const TestMesh mesh = bumpy_grid(10, true);
    const Image original = render_file("plain.gltf", plain_file(mesh, false).gltf());
    std::size_t lit = 0;
    for (float v : original.rgb) lit += v > 0;
    ASSERT_GT(lit, original.rgb.size() / 4);  // the sheet and its sky, not a black frame

    MeshoptChoice lossless;
    lossless.index_mode = "INDICES";  // every index as it was (TRIANGLES may rotate a triangle's corners)
    EXPECT_EQ(render_file("m.glb", meshopt_file(mesh, lossless, false).glb()).rgb, original.rgb) << "meshopt";

    DracoChoice on_grid;
    on_grid.position_bits = 11;
    EXPECT_EQ(render_file("d.glb", draco_file(mesh, on_grid, false).glb()).rgb, original.rgb) << "draco, 11 bits";

    DracoChoice coarse = on_grid;
    coarse.position_bits = 8;  // control: a step of 2047 / 255, the geometry moves
    EXPECT_NE(render_file("d8.glb", draco_file(mesh, coarse, false).glb()).rgb, original.rgb) << "draco, 8 bits";
}
