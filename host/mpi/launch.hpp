#pragma once
// Whether this clpath runs as one rank of an MPI job, and the job if so.
// Built with or without an MPI library: without one, being launched as
// several ranks is an error said plainly.
#include <string>

namespace clpath {

class ProcessGroup;

// Called first thing in main(): starts MPI when an MPI launcher (mpirun,
// srun) started several ranks. In a build without MPI that is an error, said
// plainly rather than rendering the same image N times.
void start_mpi_if_launched(int* argc, char*** argv);
// The job, or nullptr when not launched as several ranks.
ProcessGroup* mpi_job();
// This process's rank and the number of ranks (0 and 1 outside MPI).
int mpi_rank();
int mpi_size();
// "rank R (host): " for messages of a rank of a job of several, else "".
std::string rank_prefix();
// Ends MPI (at the end of main); or, after an error on any rank, every rank.
void finish_mpi(bool failed);

}  // namespace clpath
