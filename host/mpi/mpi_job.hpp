#pragma once
// One image rendered over the ranks of an MPI job: rank 0 hands out chunks of
// samples (render/chunks.hpp) on request, every rank renders them on its own
// devices, and the exact per-pixel sums (render/exact_film.hpp) are reduced to
// rank 0 by integer addition, so the image is the same bits however many ranks
// and devices took part. Only rank 0 writes files.
//
// All MPI calls are made from the thread that initialised MPI
// (MPI_THREAD_FUNNELED): device threads ask for chunks through a local queue
// that this thread serves.
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <memory>

#include "render/chunks.hpp"
#include "render/device_farm.hpp"
#include "render/exact_film.hpp"
#include "render/process_group.hpp"

namespace clpath {

class RemoteChunks;

class MpiJob : public ProcessGroup {
public:
    MpiJob(int* argc, char*** argv);
    ~MpiJob();
    MpiJob(const MpiJob&) = delete;
    MpiJob& operator=(const MpiJob&) = delete;

    int rank() const override { return rank_; }
    int size() const override { return size_; }
    const std::string& host() const { return host_; }

    // Ends every rank at once (a rank's error must not leave the others waiting).
    [[noreturn]] void abort(int code);

    // Throws clpath::Error on every rank, naming the ranks whose value differs
    // from rank 0's (e.g. a hash of the scene and settings).
    void check_same(std::uint64_t value, const std::string& what) override;

    // Rank 0: `lead_queue`. Other ranks: a fresh source fed by run_chunks
    // with the chunks rank 0 hands out.
    ChunkSource& chunk_source(ChunkQueue& lead_queue) override;
    // Rank 0: serves `lead_queue` to the other ranks until each has said it
    // is finished, calling poll() between messages, while `farm` renders this
    // rank's share. Other ranks: fetch chunks from rank 0 while `farm`
    // renders. Returns when this rank's farm is finished and, on rank 0, every
    // rank has said goodbye.
    void run_chunks(ChunkQueue& lead_queue, DeviceFarm& farm, const std::function<void()>& poll) override;

    void reduce_film(ExactFilm& film) override;
    void sum_films(ExactFilm& film) override;
    std::vector<std::string> gather_bytes(const std::string& mine) override;
    std::vector<DeviceShare> gather_shares(const std::vector<DeviceShare>& local) override;

private:
    int rank_ = 0, size_ = 1;
    std::string host_;
    std::unique_ptr<RemoteChunks> remote_;
};

// The chunk source of a rank other than 0: device threads wait here for the
// chunks MpiJob::run_chunks fetches from rank 0.
class RemoteChunks : public ChunkSource {
public:
    std::optional<Chunk> next() override;
    // No more chunks: every waiting and later next() returns nothing.
    void close();

private:
    friend class MpiJob;
    std::mutex mutex_;
    std::condition_variable cv_;
    int waiting_ = 0;
    std::vector<Chunk> ready_;
    bool exhausted_ = false;
};

}  // namespace clpath
