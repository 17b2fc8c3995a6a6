#include "render/render_hash.hpp"

#include <filesystem>
#include <string>

#include "cl/program.hpp"

namespace clpath {
namespace {

class Hasher {
public:
    template <class T>
    void add(const T* data, std::size_t count) {
        h_ = fnv1a64(data, count * sizeof(T), h_);
    }
    template <class T>
    void add(const std::vector<T>& v) {
        const std::uint64_t n = v.size();
        add(&n, 1);
        add(v.data(), v.size());
    }
    template <class T>
    void value(const T& v) { add(&v, 1); }
    void text(const std::string& s) { add(std::vector<char>(s.begin(), s.end())); }
    std::uint64_t get() const { return h_; }

private:
    std::uint64_t h_ = kFnv1a64Seed;
};

}  // namespace

std::uint64_t render_hash(const Scene& s, const RenderSettings& r) {
    Hasher h;
    h.add(s.vertices);
    h.add(s.triangle_material);
    h.add(s.triangle_object);
    h.add(s.materials);
    h.add(s.normals);
    for (const auto& l : s.lights) {
        h.value(l.type);
        h.value(l.position);
        h.value(l.direction);
        h.value(l.intensity);
        h.value(l.spot_inner_degrees);
        h.value(l.spot_outer_degrees);
    }
    const Environment& e = s.environment;
    h.value(e.color);
    h.text(e.image);
    std::error_code ec;  // the image's size stands for its content: ranks may see other copies
    h.value(e.image.empty() ? std::uintmax_t(0) : std::filesystem::file_size(e.image, ec));
    h.value(e.scale);
    h.value(e.rotation_degrees);
    h.value(e.importance_sampled);
    const CameraData cam = camera_data(s.camera);
    h.value(cam);
    h.value(s.camera.width);
    h.value(s.camera.height);
    for (std::uint32_t v : {r.integrator, r.max_depth, r.rr_rule, r.rr_min_depth, r.hemisphere, r.seed})
        h.value(v);
    h.value(r.ao_distance);
    h.value(r.all_features);
    h.value(std::uint32_t(r.light_sampler));
    h.value(r.accel);
    h.value(r.bvh.max_leaf_size);
    h.value(r.bvh.bins);
    return h.get();
}

}  // namespace clpath
