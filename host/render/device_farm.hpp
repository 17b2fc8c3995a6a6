#pragma once
// One renderer per OpenCL device, each on its own host thread, all taking
// chunks of samples from one source and adding their totals to one exact
// film. The image is the same bits whichever device rendered which chunk.
#include <atomic>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "cl/device.hpp"
#include "render/chunks.hpp"
#include "render/exact_film.hpp"
#include "render/prepared_scene.hpp"
#include "render/renderer.hpp"

namespace clpath {

// What one device did.
struct DeviceShare {
    std::string device;
    std::uint64_t chunks = 0;
    std::uint64_t samples_per_pixel = 0;  // its share of the image's samples
    std::uint64_t rays = 0, nonfinite = 0;
    double busy_seconds = 0;  // from its first chunk's start to its last one's end
};

class DeviceFarm {
public:
    // The film starts from `start`, holding `start_chunks` (a resumed render), else empty.
    DeviceFarm(std::vector<DeviceInfo> devices, const Scene& scene, const RenderSettings& settings,
               ExactFilm start = {}, std::vector<std::uint64_t> start_chunks = {});
    ~DeviceFarm();
    DeviceFarm(const DeviceFarm&) = delete;
    DeviceFarm& operator=(const DeviceFarm&) = delete;

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

    // A consistent copy of the film and the chunks it holds, at any time.
    ExactFilm snapshot(std::vector<std::uint64_t>* done_chunks = nullptr) const;
    const std::vector<DeviceShare>& shares() const { return shares_; }
    const BvhStats& bvh_stats() const;

private:
    void run_device(std::size_t i, ChunkSource& source);

    std::vector<DeviceInfo> devices_;
    RenderSettings settings_;
    Camera scene_camera_;
    std::shared_ptr<const PreparedScene> prepared_;
    mutable std::mutex mutex_;
    ExactFilm film_;
    std::vector<std::uint64_t> done_;
    std::vector<DeviceShare> shares_;
    std::vector<std::thread> threads_;
    std::atomic<int> running_{0};
    std::atomic<std::uint64_t> spp_{0};
    std::atomic<bool> cancel_{false};
    std::exception_ptr error_;
    std::function<void(std::uint64_t)> on_chunk_;
};

}  // namespace clpath
