#include "mpi/mpi_job.hpp"

#include <mpi.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <thread>

#include "util/error.hpp"

namespace clpath {
namespace {

enum Tag : int { kTagRequest = 1, kTagReply = 2, kTagGoodbye = 3 };

// A chunk on the wire: valid = 0 means "no more chunks".
struct WireChunk {
    std::uint64_t index;
    std::uint32_t first_sample, samples, valid, pad;
};

void check(int rc, const char* what) {
    if (rc != MPI_SUCCESS) {
        char msg[MPI_MAX_ERROR_STRING];
        int len = 0;
        MPI_Error_string(rc, msg, &len);
        throw Error(std::string(what) + " failed: " + std::string(msg, std::size_t(len)));
    }
}

// 128-bit integer addition for MPI_Reduce: exact, so the reduction order MPI
// chooses cannot change the result.
void add_fixed128(void* in, void* inout, int* len, MPI_Datatype*) {
    const auto* a = static_cast<const Fixed128*>(in);
    auto* b = static_cast<Fixed128*>(inout);
    for (int i = 0; i < *len; ++i) b[i] += a[i];
}

// The 128-bit fixed-point sums as an MPI type with their addition, freed on
// every way out (a failed MPI call throws).
struct FixedSum {
    MPI_Datatype type;
    MPI_Op op;
    FixedSum() {
        check(MPI_Op_create(&add_fixed128, 1, &op), "MPI_Op_create");
        const int rc = MPI_Type_contiguous(int(sizeof(Fixed128)), MPI_BYTE, &type);
        if (rc != MPI_SUCCESS) MPI_Op_free(&op);
        check(rc, "MPI_Type_contiguous");
        MPI_Type_commit(&type);
    }
    ~FixedSum() {
        MPI_Op_free(&op);
        MPI_Type_free(&type);
    }
    FixedSum(const FixedSum&) = delete;
    FixedSum& operator=(const FixedSum&) = delete;
};

// Blocks of at most this many sums per call, so that buffers stay small and counts fit an int.
constexpr std::size_t kFixedBlock = 1 << 20;

}  // namespace

MpiJob::MpiJob(int* argc, char*** argv) {
    int provided = 0;
    check(MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
    if (provided < MPI_THREAD_FUNNELED) throw Error("the MPI library does not allow threads (MPI_THREAD_FUNNELED)");
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    char name[MPI_MAX_PROCESSOR_NAME];
    int len = 0;
    MPI_Get_processor_name(name, &len);
    host_.assign(name, std::size_t(len));
}

MpiJob::~MpiJob() { MPI_Finalize(); }

void MpiJob::abort(int code) {
    std::fflush(stdout);
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, code);
    std::_Exit(code);  // MPI_Abort does not return; this keeps [[noreturn]] true
}

void MpiJob::check_same(std::uint64_t value, const std::string& what) {
    std::vector<std::uint64_t> all(static_cast<std::size_t>(size_));
    check(MPI_Allgather(&value, 1, MPI_UINT64_T, all.data(), 1, MPI_UINT64_T, MPI_COMM_WORLD), "MPI_Allgather");
    std::string differ;
    for (int r = 1; r < size_; ++r)
        if (all[std::size_t(r)] != all[0]) differ += (differ.empty() ? "" : ", ") + std::to_string(r);
    if (!differ.empty())
        throw Error("the ranks disagree about " + what + ": rank(s) " + differ +
                    " differ from rank 0 (every rank must be given the same scene, files and options)");
}

ChunkSource& MpiJob::chunk_source(ChunkQueue& lead_queue) {
    if (rank_ == 0) return lead_queue;
    remote_ = std::make_unique<RemoteChunks>();
    return *remote_;
}

void MpiJob::run_chunks(ChunkQueue& queue, DeviceFarm& farm, const std::function<void()>& poll) {
    using namespace std::chrono_literals;
    if (rank_ == 0) {
        int goodbyes = 0;
        while (!farm.finished() || goodbyes < size_ - 1) {
            int flag = 0;
            MPI_Status st;
            check(MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st), "MPI_Iprobe");
            if (flag) {
                char dummy = 0;
                check(MPI_Recv(&dummy, 1, MPI_CHAR, st.MPI_SOURCE, st.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
                      "MPI_Recv");
                if (st.MPI_TAG == kTagGoodbye) {
                    ++goodbyes;
                } else {
                    WireChunk w{};
                    if (std::optional<Chunk> c = queue.next()) w = {c->index, c->first_sample, c->samples, 1, 0};
                    check(MPI_Send(&w, sizeof w, MPI_BYTE, st.MPI_SOURCE, kTagReply, MPI_COMM_WORLD), "MPI_Send");
                }
                continue;
            }
            if (poll) poll();
            std::this_thread::sleep_for(1ms);
        }
        return;
    }
    if (!remote_) throw Error("internal: MpiJob::run_chunks before chunk_source");
    RemoteChunks* remote = remote_.get();
    bool exhausted = false;
    while (!farm.finished()) {
        bool want = false;
        {
            std::lock_guard<std::mutex> lock(remote->mutex_);
            want = !exhausted && remote->waiting_ > int(remote->ready_.size());
        }
        if (want) {
            char dummy = 0;
            WireChunk w{};
            check(MPI_Send(&dummy, 1, MPI_CHAR, 0, kTagRequest, MPI_COMM_WORLD), "MPI_Send");
            check(MPI_Recv(&w, sizeof w, MPI_BYTE, 0, kTagReply, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "MPI_Recv");
            if (w.valid) {
                std::lock_guard<std::mutex> lock(remote->mutex_);
                remote->ready_.push_back(Chunk{w.index, w.first_sample, w.samples});
                remote->cv_.notify_all();
            } else {
                exhausted = true;
                remote->close();
            }
            continue;
        }
        if (poll) poll();
        std::this_thread::sleep_for(1ms);
    }
    remote->close();
    char dummy = 0;
    check(MPI_Send(&dummy, 1, MPI_CHAR, 0, kTagGoodbye, MPI_COMM_WORLD), "MPI_Send");
}

void MpiJob::reduce_film(ExactFilm& film) {
    const FixedSum fixed;
    std::vector<Fixed128> sum(std::min(kFixedBlock, film.sums().size()));
    for (std::size_t first = 0; first < film.sums().size(); first += kFixedBlock) {
        const int n = int(std::min(kFixedBlock, film.sums().size() - first));
        check(MPI_Reduce(film.sums().data() + first, sum.data(), n, fixed.type, fixed.op, 0, MPI_COMM_WORLD),
              "MPI_Reduce");
        if (rank_ == 0) std::copy(sum.begin(), sum.begin() + n, film.sums().begin() + std::ptrdiff_t(first));
    }
    std::uint64_t spp = film.samples_per_pixel(), total = 0;
    check(MPI_Reduce(&spp, &total, 1, MPI_UINT64_T, MPI_SUM, 0, MPI_COMM_WORLD), "MPI_Reduce");
    if (rank_ == 0) film.set_samples_per_pixel(total);
}

void MpiJob::sum_films(ExactFilm& film) {
    const FixedSum fixed;
    for (std::vector<Fixed128>* v : {&film.sums(), &film.half()})
        for (std::size_t first = 0; first < v->size(); first += kFixedBlock) {
            const int n = int(std::min(kFixedBlock, v->size() - first));
            check(MPI_Allreduce(MPI_IN_PLACE, v->data() + first, n, fixed.type, fixed.op, MPI_COMM_WORLD),
                  "MPI_Allreduce");
        }
}

std::vector<DeviceShare> MpiJob::gather_shares(const std::vector<DeviceShare>& local) {
    struct Wire {
        char device[96];
        std::uint64_t chunks, spp, rays, nonfinite, to_device, from_device;
        double busy;
        std::uint32_t kernel_shape;
    };
    std::string mine;
    for (const auto& s : local) {
        Wire w{};
        const std::string name = "rank " + std::to_string(rank_) + " (" + host_ + "): " + s.device;
        std::strncpy(w.device, name.c_str(), sizeof w.device - 1);
        w.chunks = s.chunks;
        w.spp = s.samples_per_pixel;
        w.rays = s.rays;
        w.nonfinite = s.nonfinite;
        w.busy = s.busy_seconds;
        w.to_device = s.bytes_to_device;
        w.from_device = s.bytes_from_device;
        w.kernel_shape = std::uint32_t(s.kernel_shape);
        mine.append(reinterpret_cast<const char*>(&w), sizeof w);
    }
    std::vector<DeviceShare> out;
    for (const std::string& bytes : gather_bytes(mine))
        for (std::size_t at = 0; at + sizeof(Wire) <= bytes.size(); at += sizeof(Wire)) {
            Wire w;
            std::memcpy(&w, bytes.data() + at, sizeof w);
            DeviceShare s;
            s.device = w.device;
            s.kernel_shape = KernelShape(w.kernel_shape);
            s.chunks = w.chunks;
            s.samples_per_pixel = w.spp;
            s.rays = w.rays;
            s.nonfinite = w.nonfinite;
            s.busy_seconds = w.busy;
            s.bytes_to_device = w.to_device;
            s.bytes_from_device = w.from_device;
            out.push_back(s);
        }
    return out;
}

std::vector<std::string> MpiJob::gather_bytes(const std::string& mine) {
    if (mine.size() > std::size_t(std::numeric_limits<int>::max())) throw Error("internal: an MPI message over 2 GiB");
    int count = int(mine.size());
    std::vector<int> counts(static_cast<std::size_t>(size_)), offsets(static_cast<std::size_t>(size_));
    check(MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Gather");
    long long total = 0;
    for (int r = 0; r < size_; ++r) {
        offsets[std::size_t(r)] = int(total);
        total += counts[std::size_t(r)];
    }
    if (total > std::numeric_limits<int>::max()) throw Error("internal: MPI messages over 2 GiB in all");
    std::string all(rank_ == 0 ? std::size_t(total) : 0, '\0');
    check(MPI_Gatherv(mine.data(), count, MPI_BYTE, all.data(), counts.data(), offsets.data(), MPI_BYTE, 0,
                      MPI_COMM_WORLD),
          "MPI_Gatherv");
    std::vector<std::string> out;
    if (rank_ == 0)
        for (int r = 0; r < size_; ++r) out.push_back(all.substr(std::size_t(offsets[std::size_t(r)]), std::size_t(counts[std::size_t(r)])));
    return out;
}

std::optional<Chunk> RemoteChunks::next() {
    std::unique_lock<std::mutex> lock(mutex_);
    ++waiting_;
    cv_.wait(lock, [&] { return !ready_.empty() || exhausted_; });
    --waiting_;
    if (ready_.empty()) return std::nullopt;
    Chunk c = ready_.front();
    ready_.erase(ready_.begin());
    return c;
}

void RemoteChunks::close() {
    std::lock_guard<std::mutex> lock(mutex_);
    exhausted_ = true;
    cv_.notify_all();
}

}  // namespace clpath
