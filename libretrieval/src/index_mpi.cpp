// SPDX-License-Identifier: GPL-3.0-or-later
// `morphex index` across MPI ranks: rank 0 plans, hands out meshes on request and commits the
// results; every other rank asks, describes, sends the row back and asks again. Messages are JSON
// text (nlohmann writes doubles with the shortest text that reads back to the same double, so a
// descriptor arrives bit for bit).
#include "morphex/index_mpi.h"

#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <deque>
#include <filesystem>
#include <future>
#include <optional>
#include <stdexcept>
#include <thread>

#include "index_internal.h"
#include "morphex/internal/modules.h"
#include "morphex/internal/stopwatch.h"
#include "mpi_transport.h"

namespace morphex {
namespace {

namespace fs = std::filesystem;
using detail::PendingMesh;

// Worker -> rank 0: "give me a mesh" (empty) or a described row (JSON), which also asks for more.
constexpr int kTagRequest = 1;
constexpr int kTagTask = 2;  // rank 0 -> worker: a mesh to describe (JSON)
constexpr int kTagStop = 3;  // rank 0 -> worker: nothing left

// MPI, from the module morphex_mpi.so (mpi_transport.h), loaded by the first MpiSession. Its
// libraries' symbols are made global: Open MPI's own plugins, which it loads, look for them.
const detail::MpiTransport& mpi() {
  static const detail::MpiTransport* transport = [] {
    const LoadedModule module = open_module(detail::kMpiModule, true);
    const auto get =
        reinterpret_cast<detail::GetMpiTransport>(module_symbol(module, detail::kMpiTransport));
    if (!get)
      throw ModuleError(
          detail::kMpiModule,
          "MPI is not available: " +
              (module.error.empty() ? std::string("the module has no ") + detail::kMpiTransport
                                    : module.error));
    return get();
  }();
  return *transport;
}

// A message found by probe(): where it is from, its tag and size.
struct Probed {
  int source = 0, tag = 0, size = 0;
};

// The next message from `from` (-1: any) with `tag` (-1: any): waits when `wait`, else nullopt
// when none is there yet.
std::optional<Probed> probe(int from, int tag, bool wait) {
  Probed p;
  if (!mpi().probe(from, tag, wait, &p.source, &p.tag, &p.size)) return std::nullopt;
  return p;
}

void send_text(const std::string& text, int to, int tag) {
  mpi().send(text.data(), int(text.size()), to, tag);
}

std::string receive_text(const Probed& probed) {
  std::string text(std::size_t(probed.size), '\0');
  mpi().receive(text.data(), probed.size, probed.source, probed.tag);
  return text;
}

nlohmann::json row_to_json(const IndexedMesh& m) {
  return {{"name", m.name},       {"path", m.path},
          {"hash", m.hash},       {"status", m.status},
          {"error", m.error},     {"repair", m.repair},
          {"faces", m.faces},     {"volume", m.volume},
          {"seconds", m.seconds}, {"descriptors", m.descriptors}};
}

IndexedMesh row_from_json(const nlohmann::json& j, const std::string& settings) {
  IndexedMesh m;
  m.name = j.at("name");
  m.path = j.at("path");
  m.hash = j.at("hash");
  m.settings = settings;
  m.status = j.at("status");
  m.error = j.at("error");
  m.repair = j.at("repair");
  m.faces = j.at("faces");
  m.volume = j.at("volume");
  m.seconds = j.at("seconds");
  m.descriptors = j.at("descriptors").get<std::map<std::string, std::vector<double>>>();
  return m;
}

nlohmann::json task_to_json(const PendingMesh& p) {
  return {{"file", p.item.file}, {"path", p.item.path}, {"name", p.item.name}, {"hash", p.hash}};
}

PendingMesh task_from_json(const nlohmann::json& j) {
  return {{j.at("file"), j.at("path"), j.at("name")}, j.at("hash"), 0};
}

// A mesh described anywhere: never throws, an unexpected error is recorded as the mesh's failure.
IndexedMesh describe_safely(const IndexPipeline& pipeline, const PendingMesh& mesh,
                            const std::string& settings) {
  try {
    return detail::describe_mesh(pipeline, mesh, settings);
  } catch (const std::exception& e) {
    IndexedMesh failed;
    failed.name = mesh.item.name;
    failed.path = mesh.item.path;
    failed.hash = mesh.hash;
    failed.settings = settings;
    failed.status = "failed";
    failed.error = e.what();
    return failed;
  }
}

void pause() {
  std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

// Every rank but 0: ask, describe, send the row back (which asks again), until told to stop.
void serve(const IndexPipeline& pipeline) {
  const std::string settings = pipeline.settings();
  send_text("", 0, kTagRequest);
  for (;;) {
    std::optional<Probed> status;
    while (!(status = probe(0, -1, false))) pause();
    const std::string text = receive_text(*status);
    if (status->tag == kTagStop) return;
    const PendingMesh mesh = task_from_json(nlohmann::json::parse(text));
    send_text(row_to_json(describe_safely(pipeline, mesh, settings)).dump(), 0, kTagRequest);
  }
}

// Rank 0 after an error: answers every rank's next message with a stop (discarding what they
// send), so that none is left waiting when rank 0 reports the error and the job ends.
void release(int serving) {
  while (serving > 0) {
    const Probed status = *probe(-1, kTagRequest, true);
    receive_text(status);
    send_text("", status.source, kTagStop);
    --serving;
  }
}

// Rank 0: hands out `pending` in order to whichever rank asks, describes on its own worker thread
// too, and commits every row as it arrives. `serving` counts the ranks not yet told to stop.
void lead(detail::IndexRun& run, const IndexPipeline& pipeline,
          const std::vector<PendingMesh>& pending, int& serving) {
  std::deque<const PendingMesh*> queue;
  for (const PendingMesh& p : pending) queue.push_back(&p);
  std::optional<std::future<IndexedMesh>> local;
  while (serving > 0 || local || !queue.empty()) {
    bool busy = false;
    if (!local && !queue.empty()) {
      const PendingMesh* next = queue.front();
      queue.pop_front();
      local = std::async(std::launch::async,
                         [&, next] { return describe_safely(pipeline, *next, run.settings()); });
    }
    if (local && local->wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
      run.commit(local->get());
      local.reset();
      busy = true;
    }
    if (const std::optional<Probed> status = probe(-1, kTagRequest, false)) {
      const std::string text = receive_text(*status);
      if (!text.empty()) run.commit(row_from_json(nlohmann::json::parse(text), run.settings()));
      if (queue.empty()) {
        send_text("", status->source, kTagStop);
        --serving;
      } else {
        send_text(task_to_json(*queue.front()).dump(), status->source, kTagTask);
        queue.pop_front();
      }
      busy = true;
    }
    if (!busy) pause();
  }
}

}  // namespace

MpiSession::MpiSession() {
  if (!mpi().init(&rank_, &size_, &local_size_)) throw std::runtime_error("MPI_Init_thread failed");
}

MpiSession::~MpiSession() {
  mpi().finalize();
}

IndexSummary index_meshes_mpi(MpiSession& session, const std::string& db_path,
                              const IndexPipeline& pipeline, const std::vector<IndexItem>& items,
                              const IndexCallback& on_mesh, const IndexOptions& options) {
  const tbb::global_control limit(
      tbb::global_control::max_allowed_parallelism,
      threads_per_rank(options.threads, session.ranks_on_this_node(),
                       std::max(1u, std::thread::hardware_concurrency())));
  const Stopwatch clock;
  IndexSummary summary;
  if (session.rank() != 0) {
    serve(pipeline);
  } else {
    int serving = session.size() - 1;
    try {
      IndexDb db(db_path);
      detail::IndexRun run(db, pipeline, options, on_mesh);
      std::vector<PendingMesh> pending = run.plan(items);
      // Other nodes open the files by absolute path: their working folders may differ.
      for (PendingMesh& p : pending) p.item.file = fs::absolute(p.item.file).string();
      lead(run, pipeline, pending, serving);
      summary = run.finish();
    } catch (...) {  // the index cannot be opened or written: stop every rank, then report
      release(serving);
      mpi().quiet_barrier();
      throw;
    }
  }
  mpi().quiet_barrier();
  summary.seconds = clock.seconds();
  summary.processes = session.size();
  return summary;
}

}  // namespace morphex
