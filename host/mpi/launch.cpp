#include "mpi/launch.hpp"

#include <cstdlib>
#include <memory>

#include "util/error.hpp"
#include "render/process_group.hpp"
#ifdef CLPATH_WITH_MPI
#include "mpi/mpi_job.hpp"
#endif

namespace clpath {
namespace {

bool several_ranks_launched() {
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE", "MPI_LOCALNRANKS"})
        if (const char* v = std::getenv(name); v && std::atoi(v) > 1) return true;
    if (const char* v = std::getenv("SLURM_NTASKS"); v && std::atoi(v) > 1 && std::getenv("SLURM_PROCID"))
        return true;
    return false;
}

#ifdef CLPATH_WITH_MPI
std::unique_ptr<MpiJob> g_job;
#endif

}  // namespace

void start_mpi_if_launched(int* argc, char*** argv) {
    if (!several_ranks_launched()) return;
#ifdef CLPATH_WITH_MPI
    g_job = std::make_unique<MpiJob>(argc, argv);
#else
    (void)argc;
    (void)argv;
    throw Error("started as one of several MPI ranks, but this clpath was built without MPI "
                "(configure with -DCLPATH_WITH_MPI=ON and an MPI library such as libopenmpi-dev)");
#endif
}

ProcessGroup* mpi_job() {
#ifdef CLPATH_WITH_MPI
    return g_job.get();
#else
    return nullptr;
#endif
}

int mpi_rank() {
#ifdef CLPATH_WITH_MPI
    if (g_job) return g_job->rank();
#endif
    return 0;
}

int mpi_size() {
#ifdef CLPATH_WITH_MPI
    if (g_job) return g_job->size();
#endif
    return 1;
}

std::string rank_prefix() {
#ifdef CLPATH_WITH_MPI
    if (g_job && g_job->size() > 1) return "rank " + std::to_string(g_job->rank()) + " (" + g_job->host() + "): ";
#endif
    return "";
}

void finish_mpi(bool failed) {
#ifdef CLPATH_WITH_MPI
    if (!g_job) return;
    if (failed && g_job->size() > 1) g_job->abort(1);
    g_job.reset();
#else
    (void)failed;
#endif
}

}  // namespace clpath
