// SPDX-License-Identifier: GPL-3.0-or-later
// Indexing a collection across processes and machines with MPI (Open MPI or MPICH, started by
// mpirun, mpiexec or Slurm's srun). Built when MPI is found (CMake option MORPHEX_MPI, library
// morphex::retrieval_mpi); the command line uses it when it was started by an MPI launcher. MPI
// itself is loaded with the first MpiSession, from the module morphex_mpi.so that the build
// installs beside the libraries (a program that never starts a session never loads MPI).
//
// Rank 0 owns the SQLite index: it plans the run (what is not up to date), hands meshes out one
// at a time, largest first, to whichever rank asks next (so that one huge mesh does not hold the
// others back), describes meshes itself on a worker thread, and commits every result in its own
// transaction as it arrives: a killed job keeps what was committed and a re-run resumes. The other
// ranks describe what they are given and never touch the index. The meshes' files must be
// readable at the same absolute paths on every node (a shared file system).
//
// Errors: MPI failures abort the job (MPI's default error handler); a mesh that cannot be
// described is recorded as failed, as in a single-process run. A session that cannot load the
// module or start MPI throws std::runtime_error saying why.
#pragma once

#include <string>
#include <vector>

#include "morphex/index.h"

namespace morphex {

// MPI for the lifetime of the object: MPI_Init_thread on construction (funneled: only the
// constructing thread calls MPI), MPI_Finalize on destruction. One per process.
class MpiSession {
 public:
  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }
  int ranks_on_this_node() const { return local_size_; }  // they share this node's cores

 private:
  int rank_ = 0, size_ = 1, local_size_ = 1;
};

// The worker threads of each of `ranks_on_node` ranks on a node of `cores` cores: `requested` when
// the user chose a number (IndexOptions::threads, the command line's --threads), else an equal
// share of the node's cores, at least one, so that the ranks of a node do not oversubscribe it.
inline unsigned threads_per_rank(unsigned requested, int ranks_on_node, unsigned cores) {
  if (requested > 0) return requested;
  const unsigned ranks = ranks_on_node > 0 ? unsigned(ranks_on_node) : 1u;
  return cores / ranks > 0 ? cores / ranks : 1u;
}

// index_meshes (morphex/index.h) across the session's ranks; every rank calls it, each using
// threads_per_rank(options.threads, ...) worker threads. Rank 0 opens
// the index at `db_path`; `items` and on_mesh are used on rank 0 only. The summary is rank 0's
// (other ranks get an empty one). The rows stored are identical to those of a single-process run.
// When rank 0 cannot open or write the index, every rank is stopped before rank 0 throws.
IndexSummary index_meshes_mpi(MpiSession& session, const std::string& db_path,
                              const IndexPipeline& pipeline, const std::vector<IndexItem>& items,
                              const IndexCallback& on_mesh = {}, const IndexOptions& options = {});

}  // namespace morphex
