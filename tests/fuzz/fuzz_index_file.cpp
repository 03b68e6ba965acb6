// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target for index files, which are untrusted input (issue 44): any bytes, written to a
// file, are opened as a retrieval index read-only, listed, and queried and evaluated by the stored
// vectors; the stored pipeline is checked against the descriptor stages. Each may refuse the file
// only with morphex::Error (not an index, damaged, crafted); a crash, a hang or another exception
// is a finding. (The stored pipeline is not run: describing a mesh is not what is fuzzed here.)
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>

#include "fuzz_support.h"
#include "morphex/index.h"
#include "morphex/index_db.h"

namespace {

// A private file for the input, removed afterwards (with SQLite's side files).
class TemporaryIndex {
 public:
  explicit TemporaryIndex(const std::string& bytes) {
    char name[] = "/tmp/morphex-fuzz-index-XXXXXX";
    const int fd = mkstemp(name);
    if (fd < 0) morphex::fuzz::finding("cannot create a temporary file");
    path_ = name;
    if (!bytes.empty() && write(fd, bytes.data(), bytes.size()) != ssize_t(bytes.size()))
      morphex::fuzz::finding("cannot write a temporary file");
    close(fd);
  }
  ~TemporaryIndex() {
    for (const char* suffix : {"", "-wal", "-shm", "-journal"})
      std::remove((path_ + suffix).c_str());
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace morphex;
  const TemporaryIndex file(std::string(reinterpret_cast<const char*>(data), size));
  fuzz::expect_only<Error>([&] {
    IndexDb db(file.path(), IndexAccess::ReadOnly);
    const std::vector<IndexedMesh> all = db.load(false, {"*"});
    if (const auto pipeline = db.meta("pipeline")) {
      nlohmann::json document;
      try {
        document = nlohmann::json::parse(*pipeline);
      } catch (const nlohmann::json::exception&) {
        return;  // a query refuses it as damaged
      }
      require_descriptor_pipeline(document);
    }
    std::map<std::string, std::string> labels;
    for (const IndexedMesh& m : all)
      if (m.status == "ok") labels[m.name] = m.name.substr(0, 1);
    // A name that is also a file would be described by the stored pipeline: not fuzzed here.
    if (labels.empty() || std::filesystem::exists(labels.begin()->first)) return;
    query_index(db, labels.begin()->first, 3, default_descriptor_kind(), Metric::L1);
    evaluate_index(db, labels, Metric::L2);
  });
  return 0;
}
