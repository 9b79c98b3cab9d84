#pragma once
// One `tilekit pack --mpi` run as one MPI job: every rank runs the same search (the same
// subproblem list), its threads take jobs from a pool that the root rank (0) holds and hands out
// one at a time on request. When the pool runs dry while jobs still run, the root asks the rank
// with the most running jobs (itself included) to split: one of its workers gives away the untried
// alternatives of its shallowest open level (its oldest open subtree), which join the pool as
// pieces for the waiting workers (work stealing through the root; solver/work_source.hpp says how
// the counts and checkpoints of a split subproblem stay exact). Each rank checkpoints what it ran
// to its own file; the root's file is the run's (`--checkpoint F`: rank R > 0 writes F.rank-R), and
// a resume with any number of ranks merges F and every F.rank-* (checkpoints/checkpoint.hpp).
// At the end every rank sends its counters to the root, which alone stores the result.
//
// MPI calls are serialised by one mutex (MPI_THREAD_SERIALIZED); every wait polls with short
// sleeps instead of MPI's busy waiting (200 us where a worker waits on the answer; the root's
// dispatcher backs off from 100 to 800 us while no message comes; 1 ms for a rank's watch for
// split requests and a one-rank job's dispatcher), so an idle rank or the dispatcher costs no core.
// Without MPI (the build found none) start_mpi_work() throws InputError.
#include <memory>

#include "solver/work_source.hpp"

namespace tilekit::cluster {

// Whether this build has MPI.
bool mpi_built();

// Initialises MPI (once per process; finalised when the last reference goes) and returns this
// rank's work source.
std::shared_ptr<WorkSource> start_mpi_work();

}  // namespace tilekit::cluster
