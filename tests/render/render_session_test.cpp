// The render session through the render library alone, as a program embedding
// clpath runs it (no CLI, no benchmark library, no MPI): a render stopped once
// it has saved a checkpoint and resumed from that checkpoint ends in the same
// bits as one never stopped; progress and stop hooks are called; bad resumes
// are refused by name.
#include <gtest/gtest.h>

#include <unistd.h>

#include <condition_variable>
#include <filesystem>
#include <mutex>

#include "cl/device.hpp"
#include "render/checkpoint.hpp"
#include "render/render_hash.hpp"
#include "render/render_session.hpp"
#include "support/render_helpers.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

namespace fs = std::filesystem;

std::vector<DeviceInfo> one_device() { return {list_devices().at(0)}; }

std::string temp_path(const std::string& name) {
    return (fs::temp_directory_path() / ("clpath_session_" + std::to_string(::getpid()) + "_" + name)).string();
}

TEST(RenderSession, CheckpointedRenderResumesToTheSameBits) {
    const Scene scene = test::small_cornell(24, 16);
    RenderSettings settings;
    settings.seed = 7;
    SessionOptions o;
    o.spp = 48;
    o.chunk_samples = 2;
    const SessionResult reference = render_session(scene, settings, one_device(), o);
    ASSERT_EQ(reference.film.samples_per_pixel(), 48u);
    EXPECT_FALSE(reference.stopped);

    // Stopped after 4 chunks, whatever the timing: the device waits after its
    // fourth chunk until the stop has been asked for, so at most one more
    // chunk can start before the queue closes.
    const std::string checkpoint = temp_path("resume.ckpt");
    fs::remove(checkpoint);
    SessionOptions first = o;
    first.checkpoint_seconds = 3600;  // none on the clock: the one written is the stopped render's last
    first.checkpoint_path = checkpoint;
    std::mutex mutex;
    std::condition_variable cv;
    int chunks = 0;
    bool stop_asked = false;
    SessionHooks hooks;
    int starts = 0, progress_calls = 0;
    hooks.on_start = [&](const BvhStats& bvh) {
        ++starts;
        EXPECT_GT(bvh.node_count, 0u);
    };
    hooks.on_progress = [&](std::uint64_t spp) {
        ++progress_calls;
        EXPECT_LE(spp, 48u);
    };
    hooks.on_chunk = [&](std::uint64_t) {
        std::unique_lock<std::mutex> lock(mutex);
        if (++chunks == 4) cv.wait(lock, [&] { return stop_asked; });
    };
    hooks.stop_requested = [&] {
        std::lock_guard<std::mutex> lock(mutex);
        if (chunks >= 4) stop_asked = true;
        cv.notify_all();
        return stop_asked;
    };
    const SessionResult stopped = render_session(scene, settings, one_device(), first, hooks);
    EXPECT_EQ(starts, 1);
    EXPECT_GT(progress_calls, 0);
    EXPECT_TRUE(stopped.stopped);
    EXPECT_GE(stopped.film.samples_per_pixel(), 8u);
    EXPECT_LE(stopped.film.samples_per_pixel(), 10u);
    ASSERT_TRUE(fs::exists(checkpoint)) << "the stopped render saved no checkpoint";
    const Checkpoint saved = read_checkpoint(checkpoint);
    EXPECT_EQ(saved.film.samples_per_pixel(), stopped.film.samples_per_pixel());
    EXPECT_EQ(saved.film.sums(), stopped.film.sums());

    SessionOptions resume = o;
    resume.resume_path = checkpoint;
    const SessionResult resumed = render_session(scene, settings, one_device(), resume);
    EXPECT_EQ(resumed.film.samples_per_pixel(), 48u);
    EXPECT_EQ(resumed.film.sums(), reference.film.sums()) << "the resumed render differs from the uninterrupted one";
    fs::remove(checkpoint);
}

// The film stays on the device: a render in many chunks reads back one exact
// film (48 bytes a pixel) and a counter record per launch, and uploads no more
// than one in few chunks but the launches' parameters. (Before, each chunk
// moved a 32-byte-per-pixel film each way.)
TEST(RenderSession, ChunksMoveNoFilm) {
    const Scene scene = test::small_cornell(32, 24);
    const std::uint64_t pixels = 32 * 24;
    RenderSettings settings;
    SessionOptions few, many;
    few.spp = many.spp = 32;
    few.chunk_samples = 8;
    many.chunk_samples = 1;
    const SessionResult a = render_session(scene, settings, one_device(), few);
    const SessionResult b = render_session(scene, settings, one_device(), many);
    EXPECT_EQ(b.film.samples_per_pixel(), 32u);
    // At most 4 launches a chunk (render/device_farm.cpp), each reading a 16-byte Counters.
    const std::uint64_t launches = 4 * 32;
    EXPECT_LE(b.bytes_from_device, 48 * pixels + sizeof(Counters) * launches);
    EXPECT_GE(b.bytes_from_device, 48 * pixels);
    EXPECT_LE(b.bytes_to_device, a.bytes_to_device + sizeof(FrameParams) * launches);
}

TEST(RenderSession, RefusesACheckpointOfOtherSettings) {
    const Scene scene = test::small_cornell(8, 8);
    RenderSettings settings;
    Checkpoint c;
    c.render_hash = render_hash(scene, settings);
    c.plan = {4, 2};
    c.done_chunks = {0};
    c.film = ExactFilm(8, 8);
    c.film.set_samples_per_pixel(2);
    const std::string path = temp_path("other.ckpt");
    write_checkpoint(path, c);

    SessionOptions resume;
    resume.spp = 4;
    resume.chunk_samples = 2;
    resume.resume_path = path;
    const SessionResult ok = render_session(scene, settings, one_device(), resume);
    EXPECT_EQ(ok.film.samples_per_pixel(), 4u);
    RenderSettings other = settings;
    other.seed = 1;
    try {
        render_session(scene, other, one_device(), resume);
        FAIL() << "a checkpoint of another seed was resumed";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(path + ": the checkpoint is of another scene or other settings"),
                  std::string::npos)
            << e.what();
    }
    resume.spp = 8;
    try {
        render_session(scene, settings, one_device(), resume);
        FAIL() << "a checkpoint of another sample count was resumed";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("render of 4 samples in chunks of 2"), std::string::npos) << e.what();
    }
    fs::remove(path);
}

}  // namespace
}  // namespace clpath
