#pragma once
// The processes one render is spread over (the ranks of an MPI job), as the
// chunked, checkpointed render loop sees them. The render library defines
// this interface and never links MPI; host/mpi/ implements it. Process 0
// leads: it serves the chunk queue to the others and ends with the whole
// image.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "render/chunks.hpp"
#include "render/device_farm.hpp"
#include "render/exact_film.hpp"

namespace clpath {

class ProcessGroup {
public:
    virtual ~ProcessGroup() = default;

    virtual int rank() const = 0;
    virtual int size() const = 0;
    bool leads() const { return rank() == 0; }

    // Throws clpath::Error on every process, naming the ones whose value
    // differs from process 0's (e.g. a hash of the scene and settings).
    virtual void check_same(std::uint64_t value, const std::string& what) = 0;

    // Where this process's devices take chunks: `lead_queue` itself on the
    // lead; elsewhere, chunks fetched from the lead by run_chunks.
    virtual ChunkSource& chunk_source(ChunkQueue& lead_queue) = 0;
    // The lead serves `lead_queue` to the others until each has finished,
    // others fetch from it, while `farm` renders this process's share;
    // poll() runs between messages. Returns when this process's farm is
    // finished and, on the lead, every process has finished.
    virtual void run_chunks(ChunkQueue& lead_queue, DeviceFarm& farm, const std::function<void()>& poll) = 0;

    // Sums every process's film into the lead's (the others' are left unchanged).
    virtual void reduce_film(ExactFilm& film) = 0;
    // Sums every process's sums and half film (adaptive sampling) into every
    // process's film, exactly: each process then holds the same film and
    // takes the same decisions. Collective: every process calls it.
    virtual void sum_films(ExactFilm& film) = 0;
    // Every process's device shares, on the lead (named "rank R (host): device").
    virtual std::vector<DeviceShare> gather_shares(const std::vector<DeviceShare>& local) = 0;
    // Every process's bytes, on the lead in rank order (empty elsewhere).
    virtual std::vector<std::string> gather_bytes(const std::string& mine) = 0;
};

}  // namespace clpath
