#pragma once
// One renderer per OpenCL device, each on its own host thread, all taking
// chunks of samples from one source. Each device adds its chunks' totals to an
// exact film of its own, on the device (render/device_exact_film.hpp); the
// host reads them only when asked for the image (snapshot: a checkpoint, the
// end) and adds them as integers, so the image is the same bits whichever
// device rendered which chunk, and no film crosses the bus per chunk.
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "cl/device.hpp"
#include "render/chunks.hpp"
#include "render/device_exact_film.hpp"
#include "render/exact_film.hpp"
#include "render/prepared_scene.hpp"
#include "render/renderer.hpp"

namespace clpath {

// What one device did.
struct DeviceShare {
    std::string device;
    KernelShape kernel_shape = KernelShape::Mega;  // the shape its kernels took (resolve_kernel_shape)
    std::uint64_t chunks = 0;
    std::uint64_t samples_per_pixel = 0;  // its share of the image's samples
    std::uint64_t rays = 0, nonfinite = 0;
    double busy_seconds = 0;  // from its first chunk's start to its last one's end
    std::uint64_t bytes_to_device = 0, bytes_from_device = 0;  // scene, films, counters: every transfer
};

class DeviceFarm {
public:
    // The film starts from `start`, holding `start_chunks` (a resumed render), else empty.
    DeviceFarm(std::vector<DeviceInfo> devices, const Scene& scene, const RenderSettings& settings,
               ExactFilm start = {}, std::vector<std::uint64_t> start_chunks = {});
    ~DeviceFarm();
    DeviceFarm(const DeviceFarm&) = delete;
    DeviceFarm& operator=(const DeviceFarm&) = delete;

    // Adaptive sampling (render/adaptive.hpp), set before start(): chunks come
    // in passes of pass_chunks, and a device that takes a chunk of pass q
    // waits (answering snapshots) until open_pass(q) gives that pass's mask;
    // the devices keep the half film.
    void use_passes(std::uint64_t pass_chunks);
    // The pass whose chunks may now be rendered, and its pixels (a mask as
    // Renderer::set_active_pixels takes).
    void open_pass(std::uint64_t pass, std::shared_ptr<const std::vector<std::uint8_t>> mask);
    // No pass opens any more: a device waiting with a chunk drops it and ends.
    void close_passes();
    // Chunks of a pass added to the film so far.
    std::uint64_t chunks_done_in_pass(std::uint64_t pass) const;

    // Starts one thread per device. on_chunk (optional) is called from the
    // device's thread after each chunk is added, with the film's sample count.
    void start(ChunkSource& source, std::function<void(std::uint64_t)> on_chunk = {});
    // Asks devices to abandon the chunk they are on at its next launch boundary
    // (an interrupted render keeps only whole chunks).
    void cancel() { cancel_ = true; }
    bool finished() const { return running_ == 0; }
    // Samples per pixel in the film so far (chunks finished, plus any resumed).
    std::uint64_t samples_per_pixel() const { return spp_; }
    // Joins the threads; rethrows the first device's error.
    void wait();

    // A consistent copy of the film and the chunks it holds, at any time:
    // every device that has rendered a chunk reads its film back at its next
    // chunk boundary (so this waits for up to one chunk), and the films are
    // added. After wait(), the final image.
    ExactFilm snapshot(std::vector<std::uint64_t>* done_chunks = nullptr) const;
    // After wait(): what each device did (rays and bytes are counted when a device finishes).
    std::vector<DeviceShare> shares() const;
    const BvhStats& bvh_stats() const;
    const SceneSummary& scene_summary() const;
    // The bytes one device holds for the scene: the first device's scene
    // buffers as uploaded, else (before it uploads) DeviceScene::memory_needs, summed.
    std::size_t scene_device_bytes() const;

private:
    // A device's film as it last read it back, and the chunks in it.
    struct Published {
        ExactFilm film;
        std::vector<std::uint64_t> done;
        std::uint64_t answered = 0;  // the snapshot request it answered last
        bool has_chunks = false;     // it has added a chunk to its device film
        bool exited = false;         // its thread has ended (its film is final)
    };

    void run_device(std::size_t i, ChunkSource& source);
    // On device i's thread: reads its film back when a snapshot waits for it.
    void answer_snapshot(std::size_t i, const DeviceExactFilm& film, const std::vector<std::uint64_t>& done,
                         bool final);

    std::vector<DeviceInfo> devices_;
    RenderSettings settings_;
    Camera scene_camera_;
    std::shared_ptr<const PreparedScene> prepared_;
    mutable std::mutex mutex_;
    mutable std::condition_variable published_cv_;
    mutable std::uint64_t snapshot_request_ = 0;
    ExactFilm start_;                      // a resumed render's sums
    std::vector<std::uint64_t> start_done_;  // and its chunks
    std::vector<Published> published_;
    std::vector<DeviceShare> shares_;
    std::size_t scene_bytes_ = 0;  // the first device's scene buffers, once uploaded
    std::vector<std::thread> threads_;
    std::atomic<int> running_{0};
    std::atomic<std::uint64_t> spp_{0};
    std::atomic<bool> cancel_{false};
    std::exception_ptr error_;
    std::function<void(std::uint64_t)> on_chunk_;
    // Adaptive passes (0: none), the pass open and its mask, the chunks done per pass.
    std::uint64_t pass_chunks_ = 0;
    std::uint64_t open_pass_ = 0;
    bool pass_opened_ = false, passes_closed_ = false;
    std::shared_ptr<const std::vector<std::uint8_t>> pass_mask_;
    std::map<std::uint64_t, std::uint64_t> pass_done_;
    mutable std::condition_variable pass_cv_;
};

}  // namespace clpath
