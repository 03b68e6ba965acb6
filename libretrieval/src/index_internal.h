// SPDX-License-Identifier: GPL-3.0-or-later
// The phases of indexing a collection, shared by the single-process run (index.cpp) and the MPI
// run (index_mpi.cpp): plan what needs describing, describe one mesh, commit its result. Both runs
// go through the same three functions, so that they store identical rows.
#pragma once

#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include "morphex/index.h"

namespace morphex::detail {

// A mesh that needs describing, with its content hash and file size (largest first).
struct PendingMesh {
  IndexItem item;
  std::string hash;
  std::uintmax_t bytes = 0;
};

// The state of a run that every phase updates: the summary, the progress and the callback.
class IndexRun {
 public:
  IndexRun(IndexDb& db, const IndexPipeline& pipeline, const IndexOptions& options,
           const IndexCallback& on_mesh);
  // Refuses (InputError, nothing written) items that would leave the index with meshes described
  // under other settings, then stores the pipeline. Unreadable files are recorded as failed at
  // once, meshes up to date (or failed before with this content and these settings, unless
  // retry_failed) are skipped; the rest is returned, largest file first, and sets the progress
  // total.
  std::vector<PendingMesh> plan(const std::vector<IndexItem>& items);
  // Stores one described mesh in its own transaction and reports it.
  void commit(const IndexedMesh& mesh);
  // After a pipeline stage: `meshes` is the run's finished work counted in meshes.
  void stage_done(double meshes);
  IndexSummary finish();
  const std::string& settings() const { return settings_; }

 private:
  void report(const IndexItem& item, const std::string& error);
  void require_one_setting(const std::vector<IndexItem>& items);
  IndexDb& db_;
  IndexOptions options_;
  const IndexCallback& on_mesh_;
  std::string settings_, document_, sets_;
  IndexSummary summary_;
  IndexProgress progress_;
  std::mutex mutex_;  // commits and stage reports come from different worker threads
};

// The pipeline's report for one mesh as the row to store.
IndexedMesh described_from_report(const pipeline::InputReport& report, const PendingMesh& mesh,
                                  const std::string& settings);
// Runs the pipeline on one mesh (what an MPI worker does).
IndexedMesh describe_mesh(const IndexPipeline& pipeline, const PendingMesh& mesh,
                          const std::string& settings);

}  // namespace morphex::detail
