#include "bench/embree_scene.hpp"

#if defined(__SSE__)  // MXCSR
#include <xmmintrin.h>
#endif

namespace clpath {

#if defined(__SSE__)
EmbreeThreadFloatMode::EmbreeThreadFloatMode() : saved_(_mm_getcsr()) {
    constexpr unsigned kFlushToZero = 0x8000, kDenormalsAreZero = 0x0040;  // MXCSR bits 15 and 6
    _mm_setcsr(saved_ | kFlushToZero | kDenormalsAreZero);
}
EmbreeThreadFloatMode::~EmbreeThreadFloatMode() { _mm_setcsr(saved_); }
#else
EmbreeThreadFloatMode::EmbreeThreadFloatMode() {}  // no MXCSR (Embree on ARM through SSE2NEON)
EmbreeThreadFloatMode::~EmbreeThreadFloatMode() {}
#endif

const char* embree_mode_name(EmbreeMode mode) { return mode == EmbreeMode::Robust ? "robust" : "default"; }

std::string describe_embree_mode(EmbreeMode mode) {
    return mode == EmbreeMode::Robust ? "robust mode (RTC_SCENE_FLAG_ROBUST)" : "default mode (no RTC_SCENE_FLAG_ROBUST)";
}

}  // namespace clpath

#if CLPATH_WITH_EMBREE
#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <thread>

#include "util/error.hpp"

namespace clpath {

namespace {

// A triangle geometry over vertices (three per triangle), attached to scene.
void attach_triangles(RTCDevice device, RTCScene scene, const std::vector<glm::vec3>& vertices, const EmbreeScene& owner) {
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(geom, RTC_BUILD_QUALITY_HIGH);
    const std::size_t n = vertices.size() / 3;
    // Embree's own buffers: it pads them for its 16-byte loads.
    auto* v = static_cast<float*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
    auto* idx = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
    owner.check("allocating the geometry");
    for (std::size_t i = 0; i < 3 * n; ++i) {
        v[3 * i] = vertices[i].x;
        v[3 * i + 1] = vertices[i].y;
        v[3 * i + 2] = vertices[i].z;
        idx[i] = unsigned(i);
    }
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
}

}  // namespace

void EmbreeScene::open(int threads, EmbreeMode mode) {
    mode_ = mode;
    threads_ = threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
    device_ = rtcNewDevice(("threads=" + std::to_string(threads_)).c_str());
    if (!device_) throw Error("Embree: cannot create a device (error " + std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
}

RTCScene EmbreeScene::new_scene() const {
    RTCScene s = rtcNewScene(device_);
    // Robust mode: watertight edges, as the kernels' and the CPU reference's
    // triangle tests. The default mode leaves the flags as Embree's users do.
    if (mode_ == EmbreeMode::Robust) rtcSetSceneFlags(s, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(s, RTC_BUILD_QUALITY_HIGH);
    return s;
}

EmbreeScene::EmbreeScene(const std::vector<glm::vec3>& vertices, int threads, EmbreeMode mode) {
    open(threads, mode);
    const auto t0 = std::chrono::steady_clock::now();
    scene_ = new_scene();
    attach_triangles(device_, scene_, vertices, *this);
    rtcCommitScene(scene_);
    check("building the scene");
    build_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

EmbreeScene::EmbreeScene(const std::vector<const std::vector<glm::vec3>*>& meshes,
                         const std::vector<std::pair<std::uint32_t, glm::mat4>>& placements, int threads,
                         EmbreeMode mode) {
    open(threads, mode);
    const auto t0 = std::chrono::steady_clock::now();
    for (const auto* m : meshes) {
        meshes_.push_back(new_scene());
        attach_triangles(device_, meshes_.back(), *m, *this);
        rtcCommitScene(meshes_.back());
        check("building a mesh's scene");
    }
    scene_ = new_scene();
    for (const auto& [mesh, to_world] : placements) {
        if (mesh >= meshes_.size()) throw Error("Embree: a placement names mesh " + std::to_string(mesh));
        RTCGeometry inst = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(inst, meshes_[mesh]);
        rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &to_world[0][0]);
        rtcCommitGeometry(inst);
        rtcAttachGeometry(scene_, inst);
        rtcReleaseGeometry(inst);
    }
    rtcCommitScene(scene_);
    check("building the instances' scene");
    build_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

EmbreeScene::~EmbreeScene() {
    if (scene_) rtcReleaseScene(scene_);
    for (RTCScene m : meshes_) rtcReleaseScene(m);
    if (device_) rtcReleaseDevice(device_);
}

void EmbreeScene::check(const char* what) const {
    const RTCError e = rtcGetDeviceError(device_);
    if (e != RTC_ERROR_NONE) throw Error(std::string("Embree: ") + what + " failed (error " + std::to_string(int(e)) + ")");
}

}  // namespace clpath
#endif
