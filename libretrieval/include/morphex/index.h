// SPDX-License-Identifier: GPL-3.0-or-later
// A retrieval index of a mesh collection: meshes described by a descriptor pipeline (JSON, the
// pipelines engine) into an IndexDb (morphex/index_db.h), queried for nearest neighbours and
// evaluated against class labels. `morphex index`, `query` and `evaluate` and the Python
// morphex.Index are thin layers over these functions.
//
// Errors: a bad pipeline throws pipeline::PipelineError (every problem with its location) before
// any mesh is described; a mesh that cannot be described is recorded as failed and reported to
// the callback, and the others go on; a query that cannot be answered throws InputError naming
// the mesh or the index.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "morphex/descriptors.h"
#include "morphex/index_db.h"
#include "morphex/pipeline.h"
#include "morphex/retrieval.h"

namespace morphex {

// The default descriptor pipeline: read ${input}, then describe with default settings.
extern const char* const kDefaultIndexPipeline;

// A validated descriptor pipeline with its variables, as an index runs it.
struct IndexPipeline {
  nlohmann::json document;        // solidify stages inserted when asked
  std::string name;               // the file name (or "default"), for messages
  pipeline::Variables variables;  // bound on every run (--set)
  // What a mesh's stored descriptors are valid for: this pipeline, these variables and this
  // version of the descriptors. A mesh indexed under other settings is described again.
  std::string settings() const;
};

// `document` (nullptr: kDefaultIndexPipeline) validated with ${input} and ${stem} deferred; it
// must have a describe stage. With `repair`, a solidify stage (morphex/solidify.h) follows every
// read and takes the read's tag, so that what read the mesh reads the solid: valid solids pass
// unchanged, soups, open, flipped or self-intersecting meshes become one (recorded per mesh);
// `repair_budget` is the work budget of its exact repair (RepairOptions::budget; default: the
// repair's). Throws pipeline::PipelineError.
IndexPipeline make_index_pipeline(const nlohmann::json* document, const std::string& name,
                                  pipeline::Variables variables, bool repair,
                                  std::optional<double> repair_budget = std::nullopt);

// Throws pipeline::PipelineError unless every stage of `document` only computes from the mesh
// being described: its stages are of the descriptor types (no `write`), every read reads
// "${input}" and no structuring element is read from a file. make_index_pipeline requires it,
// and so does a query that runs the pipeline stored in an index (index files are untrusted).
void require_descriptor_pipeline(const nlohmann::json& document);

// One mesh to index: the file the pipeline reads, and the path and name the index records (the
// same for files; bindings that index in-memory meshes record another path).
struct IndexItem {
  std::string file, path, name;
};
// path = the file's absolute path, so that an index can be updated from any folder; name = its
// stem.
IndexItem index_item(const std::string& file);

// After each mesh described (or refused): how far the run is, and the mesh's error ("" if ok).
struct IndexProgress {
  std::size_t done = 0, total = 0, failed = 0;
  // The finished share of the meshes still being described, in meshes (their finished pipeline
  // stages), so that a display can move inside a long mesh; 0 in per-mesh reports.
  double running = 0;
};
using IndexCallback =
    std::function<void(const IndexItem& item, const std::string& error, const IndexProgress&)>;

struct IndexOptions {
  // Describe again meshes that failed before with the same content and settings (by default they
  // are skipped: a mesh that cannot be described fails the same way every time).
  bool retry_failed = false;
  // Called after every pipeline stage of every mesh, one call at a time (single-process runs).
  std::function<void(const IndexProgress&)> on_stage;
  // Worker threads of this process, as the user chose them (the command line's --threads); 0:
  // the default, every core, or under MPI this node's cores shared among its ranks
  // (threads_per_rank, morphex/index_mpi.h).
  unsigned threads = 0;
};

struct IndexSummary {
  std::size_t indexed = 0;
  std::size_t skipped = 0;         // already up to date
  std::size_t skipped_failed = 0;  // failed before with this content and these settings
  std::vector<std::pair<std::string, std::string>> errors;  // (recorded path, message)
  double seconds = 0;
  int processes = 1;  // MPI ranks that described meshes
};

// Throws InputError, writing nothing, when the index holds meshes described under other settings
// that `items` does not describe again (their descriptors would not compare with the others).
// Describes every item not already up to date (same content hash and settings) and commits each
// as soon as it finishes, so that an interrupted run keeps what it committed and a re-run resumes.
// Items are described largest file first. The pipeline and its variables are stored in the index
// for queries. `on_mesh` is called from one thread at a time.
IndexSummary index_meshes(IndexDb& db, const IndexPipeline& pipeline,
                          const std::vector<IndexItem>& items, const IndexCallback& on_mesh = {},
                          const IndexOptions& options = {});

// Removes the meshes that `keys` name: a recorded path, a file's path (made absolute) or the name
// of exactly one indexed mesh. Every key is resolved before anything is removed: a key that names
// no mesh, or a name that several meshes share, throws InputError naming the index and each such
// key, and nothing is removed. Returns how many entries were removed.
std::size_t remove_indexed(IndexDb& db, const std::vector<std::string>& keys);

struct Neighbour {
  std::string name, path;
  double distance = 0;
  long long id = 0;  // the mesh's row in the index
};

// The k indexed meshes nearest to `target` by descriptor `kind` under `metric`, nearest first (ties
// by name). `target` is a mesh file, described by the index's own pipeline, or (when `by_name`)
// an indexed mesh: its recorded path, or its name when no such file exists. An indexed mesh's
// stored vector is used and it is not ranked, whether named by name or by path. Throws
// InputError, also when the index's meshes were described under several settings, or its stored
// pipeline holds other than descriptor stages.
std::vector<Neighbour> query_index(IndexDb& db, const std::string& target, std::size_t k,
                                   const std::string& kind, Metric metric, bool by_name = true);

// The steps of query_index for a mesh file, for callers that describe outside a lock on the index
// (morphex serve): the index's stored pipeline, checked as query_index checks it (only descriptor
// stages, the meshes' settings); `file` described by it (every kind of its last describe stage,
// InputError naming the file when it cannot be); and the ranking of a vector against the stored
// ones, leaving out the mesh of id `exclude`.
IndexPipeline query_pipeline(IndexDb& db);
std::map<std::string, std::vector<double>> describe_query(const IndexPipeline& pipeline,
                                                          const std::string& file);
std::vector<Neighbour> rank_index(IndexDb& db, const std::vector<double>& query, std::size_t k,
                                  const std::string& kind, Metric metric, long long exclude = -1);

struct IndexEvaluation {
  std::size_t models = 0, unlabelled = 0;  // indexed meshes with and without a label
  // Per descriptor kind stored for every labelled mesh, in descriptor_kinds() order (the same
  // kinds in the same order in all three).
  std::vector<std::pair<std::string, RetrievalScores>> scores;
  std::vector<std::pair<std::string, std::vector<ClassScores>>> per_class;
  std::vector<std::pair<std::string, PrecisionRecall>> precision_recall;
};

// Every labelled indexed mesh queried against the others (labels: model name -> class). Throws
// InputError when the labelled meshes were described under several settings.
IndexEvaluation evaluate_index(IndexDb& db, const std::map<std::string, std::string>& labels,
                               Metric metric);

}  // namespace morphex
