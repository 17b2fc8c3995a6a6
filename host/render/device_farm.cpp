#include "render/device_farm.hpp"

#include <algorithm>
#include <chrono>

#include "cl/context.hpp"
#include "render/device_scene.hpp"
#include "util/error.hpp"

namespace clpath {

DeviceFarm::DeviceFarm(std::vector<DeviceInfo> devices, const Scene& scene, const RenderSettings& settings,
                       ExactFilm start, std::vector<std::uint64_t> start_chunks)
    : devices_(std::move(devices)), settings_(settings), scene_camera_(scene.camera),
      start_(std::move(start)), start_done_(std::move(start_chunks)) {
    if (devices_.empty()) throw Error("internal: a device farm with no device");
    // The BVH, light table and environment are built once, for every device.
    prepared_ = prepare_scene(scene, settings_);
    if (start_.width() == 0) start_ = ExactFilm(scene.camera.width, scene.camera.height);
    if (start_.width() != scene.camera.width || start_.height() != scene.camera.height)
        throw Error("internal: the starting film does not match the camera");
    spp_ = start_.samples_per_pixel();
    shares_.resize(devices_.size());
    published_.resize(devices_.size());
    for (std::size_t i = 0; i < devices_.size(); ++i) {
        shares_[i].device = devices_[i].name;
        shares_[i].kernel_shape = resolve_kernel_shape(settings, devices_[i].is_gpu);
    }
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
                published_[i].exited = true;  // a snapshot must not wait for it
                published_cv_.notify_all();
            }
            --running_;
        });
}

void DeviceFarm::run_device(std::size_t i, ChunkSource& source) {
    const DeviceInfo& device = devices_[i];
    Context ctx(device);
    auto on_device = [&](auto make) {
        try {
            return make();
        } catch (const Error& e) {
            throw Error("device [" + std::to_string(device.index) + "] " + device.name + ": " + e.what());
        }
    };
    Renderer renderer = on_device([&] { return Renderer(ctx, *prepared_, settings_); });
    if (i == 0) {
        std::lock_guard<std::mutex> lock(mutex_);
        scene_bytes_ = renderer.device_scene().bytes();
    }
    DeviceExactFilm exact = on_device(
        [&] { return DeviceExactFilm(ctx, scene_camera_.width, scene_camera_.height, pass_chunks_ > 0); });
    std::vector<std::uint64_t> done;
    std::chrono::steady_clock::time_point first{}, last{};
    std::shared_ptr<const std::vector<std::uint8_t>> mask;  // the one the renderer has
    while (!cancel_) {
        const std::optional<Chunk> chunk = source.next();
        if (!chunk) break;
        if (pass_chunks_) {
            // A chunk of a pass not yet open waits for its mask, which needs
            // every chunk of the pass before in the film.
            const std::uint64_t pass = chunk->index / pass_chunks_;
            std::shared_ptr<const std::vector<std::uint8_t>> pass_mask;
            for (;;) {
                {
                    std::unique_lock<std::mutex> lock(mutex_);
                    // Woken by open_pass, close_passes and a snapshot request (to answer it).
                    pass_cv_.wait_for(lock, std::chrono::milliseconds(5), [&] {
                        return cancel_ || passes_closed_ || (pass_opened_ && open_pass_ >= pass) ||
                               (published_[i].has_chunks && published_[i].answered < snapshot_request_);
                    });
                    if (cancel_ || passes_closed_) break;
                    if (pass_opened_ && open_pass_ >= pass) {
                        if (open_pass_ != pass) throw Error("internal: a chunk of a pass already closed");
                        pass_mask = pass_mask_;
                        break;
                    }
                }
                answer_snapshot(i, exact, done, false);
            }
            if (!pass_mask) break;  // the render ended: the chunk is dropped
            if (pass_mask != mask) {
                mask = pass_mask;
                renderer.set_active_pixels(mask.get());
            }
        }
        if (first == std::chrono::steady_clock::time_point{}) first = std::chrono::steady_clock::now();
        // The film is empty (new, or emptied by the last add_chunk_to); its
        // sample count starts at the chunk's first sample index, so the
        // kernels draw that chunk's samples.
        renderer.start_chunk(chunk->first_sample);
        // A chunk is added in a few steps, so that a cancel is seen within one
        // step; the samples and their order do not depend on the steps.
        const std::uint32_t step = std::max<std::uint32_t>(1, (chunk->samples + 3) / 4);
        for (std::uint32_t n = 0; n < chunk->samples && !cancel_;) {
            const std::uint32_t k = std::min(step, chunk->samples - n);
            renderer.add_samples(k);
            n += k;
        }
        if (cancel_) break;  // an unfinished chunk is dropped whole
        renderer.add_chunk_to(exact, chunk->samples);
        done.push_back(chunk->index);
        last = std::chrono::steady_clock::now();
        std::uint64_t spp;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            if (pass_chunks_) ++pass_done_[chunk->index / pass_chunks_];
            published_[i].has_chunks = true;
            DeviceShare& s = shares_[i];
            ++s.chunks;
            s.samples_per_pixel += chunk->samples;
            s.busy_seconds = std::chrono::duration<double>(last - first).count();
            spp = spp_ += chunk->samples;
        }
        if (on_chunk_) on_chunk_(spp);
        answer_snapshot(i, exact, done, false);
    }
    const RenderStats stats = renderer.stats();
    answer_snapshot(i, exact, done, true);
    std::lock_guard<std::mutex> lock(mutex_);
    shares_[i].rays = stats.rays;
    shares_[i].nonfinite = stats.nonfinite;
    shares_[i].bytes_to_device = ctx.bytes_to_device();
    shares_[i].bytes_from_device = ctx.bytes_from_device();
}

void DeviceFarm::use_passes(std::uint64_t pass_chunks) {
    if (!threads_.empty()) throw Error("internal: use_passes after start");
    pass_chunks_ = pass_chunks;
}

void DeviceFarm::open_pass(std::uint64_t pass, std::shared_ptr<const std::vector<std::uint8_t>> mask) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (pass_opened_ && pass <= open_pass_) throw Error("internal: passes open in order");
    open_pass_ = pass;
    pass_opened_ = true;
    pass_mask_ = std::move(mask);
    pass_cv_.notify_all();
}

void DeviceFarm::close_passes() {
    std::lock_guard<std::mutex> lock(mutex_);
    passes_closed_ = true;
    pass_cv_.notify_all();
}

std::uint64_t DeviceFarm::chunks_done_in_pass(std::uint64_t pass) const {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = pass_done_.find(pass);
    return it == pass_done_.end() ? 0 : it->second;
}

void DeviceFarm::answer_snapshot(std::size_t i, const DeviceExactFilm& film, const std::vector<std::uint64_t>& done,
                                 bool final) {
    std::uint64_t request;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        request = snapshot_request_;
        if (!final && published_[i].answered >= request) return;
    }
    // Read outside the lock: the other devices go on meanwhile.
    ExactFilm f = published_[i].has_chunks ? film.read() : ExactFilm();
    std::lock_guard<std::mutex> lock(mutex_);
    published_[i].film = std::move(f);
    published_[i].done = done;
    published_[i].answered = request;
    published_[i].exited = final;
    published_cv_.notify_all();
}

void DeviceFarm::wait() {
    for (auto& t : threads_)
        if (t.joinable()) t.join();
    threads_.clear();
    if (error_) std::rethrow_exception(error_);
}

ExactFilm DeviceFarm::snapshot(std::vector<std::uint64_t>* done_chunks) const {
    std::unique_lock<std::mutex> lock(mutex_);
    const std::uint64_t request = ++snapshot_request_;
    pass_cv_.notify_all();  // devices waiting for a pass answer at once
    // A device with no chunk yet has nothing to give; one whose thread ended
    // (finished, cancelled or failed) gave its final film.
    published_cv_.wait(lock, [&] {
        for (const Published& p : published_)
            if (p.has_chunks && !p.exited && p.answered < request) return false;
        return true;
    });
    ExactFilm film = start_;
    std::vector<std::uint64_t> done = start_done_;
    for (const Published& p : published_) {
        if (p.film.width() == 0) continue;
        film.add(p.film);
        done.insert(done.end(), p.done.begin(), p.done.end());
    }
    if (done_chunks) *done_chunks = std::move(done);
    return film;
}

std::vector<DeviceShare> DeviceFarm::shares() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return shares_;
}

const BvhStats& DeviceFarm::bvh_stats() const { return prepared_->summary.bvh_stats; }

const SceneSummary& DeviceFarm::scene_summary() const { return prepared_->summary; }

std::size_t DeviceFarm::scene_device_bytes() const {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (scene_bytes_) return scene_bytes_;
    }
    std::size_t n = 0;
    // As the first device would hold it (devices of other kinds may hold other node layouts).
    for (const auto& [what, bytes] : DeviceScene::memory_needs(*prepared_, DeviceScene::device_node_layout(devices_.front(), *prepared_)))
        n += bytes;
    return n;
}

}  // namespace clpath
