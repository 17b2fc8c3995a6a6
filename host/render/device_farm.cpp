#include "render/device_farm.hpp"

#include <algorithm>
#include <chrono>

#include "cl/context.hpp"
#include "util/error.hpp"

namespace clpath {

DeviceFarm::DeviceFarm(std::vector<DeviceInfo> devices, const Scene& scene, const RenderSettings& settings,
                       ExactFilm start, std::vector<std::uint64_t> start_chunks)
    : devices_(std::move(devices)), settings_(settings), scene_camera_(scene.camera),
      film_(std::move(start)), done_(std::move(start_chunks)) {
    if (devices_.empty()) throw Error("internal: a device farm with no device");
    // The BVH, light table and environment are built once, for every device.
    prepared_ = prepare_scene(scene, settings_);
    if (film_.width() == 0) film_ = ExactFilm(scene.camera.width, scene.camera.height);
    if (film_.width() != scene.camera.width || film_.height() != scene.camera.height)
        throw Error("internal: the starting film does not match the camera");
    spp_ = film_.samples_per_pixel();
    shares_.resize(devices_.size());
    for (std::size_t i = 0; i < devices_.size(); ++i) shares_[i].device = devices_[i].name;
}

DeviceFarm::~DeviceFarm() {
    cancel_ = true;
    for (auto& t : threads_)
        if (t.joinable()) t.join();
}

void DeviceFarm::start(ChunkSource& source, std::function<void(std::uint64_t)> on_chunk) {
    on_chunk_ = std::move(on_chunk);
    running_ = int(devices_.size());
    for (std::size_t i = 0; i < devices_.size(); ++i)
        threads_.emplace_back([this, i, &source] {
            try {
                run_device(i, source);
            } catch (...) {
                std::lock_guard<std::mutex> lock(mutex_);
                if (!error_) error_ = std::current_exception();
                cancel_ = true;  // the others stop at their next launch
            }
            --running_;
        });
}

void DeviceFarm::run_device(std::size_t i, ChunkSource& source) {
    const DeviceInfo& device = devices_[i];
    Context ctx(device);
    Renderer renderer = [&] {
        try {
            return Renderer(ctx, *prepared_, settings_);
        } catch (const Error& e) {
            throw Error("device [" + std::to_string(device.index) + "] " + device.name + ": " + e.what());
        }
    }();
    // A chunk is rendered into an empty film whose sample count starts at the
    // chunk's first sample index, so the kernels draw that chunk's samples.
    FilmState empty{scene_camera_.width, scene_camera_.height, 0,
                    std::vector<AccumPixel>(std::size_t(scene_camera_.width) * std::size_t(scene_camera_.height))};
    std::chrono::steady_clock::time_point first{}, last{};
    while (!cancel_) {
        const std::optional<Chunk> chunk = source.next();
        if (!chunk) break;
        if (first == std::chrono::steady_clock::time_point{}) first = std::chrono::steady_clock::now();
        renderer.reset();
        empty.samples_per_pixel = chunk->first_sample;
        renderer.film().write_state(empty);
        // A chunk is added in a few steps, so that a cancel is seen within one
        // step; the samples and their order do not depend on the steps.
        const std::uint32_t step = std::max<std::uint32_t>(1, (chunk->samples + 3) / 4);
        for (std::uint32_t done = 0; done < chunk->samples && !cancel_;) {
            const std::uint32_t n = std::min(step, chunk->samples - done);
            renderer.add_samples(n);
            done += n;
        }
        if (cancel_) break;  // an unfinished chunk is dropped whole
        const FilmState state = renderer.film().read_state();
        const RenderStats stats = renderer.stats();
        last = std::chrono::steady_clock::now();
        std::uint64_t spp;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            film_.add_chunk(state.pixels, chunk->samples);
            done_.push_back(chunk->index);
            DeviceShare& s = shares_[i];
            ++s.chunks;
            s.samples_per_pixel += chunk->samples;
            s.rays += stats.rays;
            s.nonfinite += stats.nonfinite;
            s.busy_seconds = std::chrono::duration<double>(last - first).count();
            spp = film_.samples_per_pixel();
            spp_ = spp;
        }
        if (on_chunk_) on_chunk_(spp);
    }
}

void DeviceFarm::wait() {
    for (auto& t : threads_)
        if (t.joinable()) t.join();
    threads_.clear();
    if (error_) std::rethrow_exception(error_);
}

ExactFilm DeviceFarm::snapshot(std::vector<std::uint64_t>* done_chunks) const {
    std::lock_guard<std::mutex> lock(mutex_);
    if (done_chunks) *done_chunks = done_;
    return film_;
}

const BvhStats& DeviceFarm::bvh_stats() const { return prepared_->summary.bvh_stats; }

}  // namespace clpath
