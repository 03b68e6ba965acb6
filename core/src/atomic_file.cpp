// SPDX-License-Identifier: GPL-3.0-or-later
// Atomic output files: written to a temporary next to the target, then renamed into place, with
// a signal-safe registry of the temporaries in progress (morphex/atomic_files.h).
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "morphex/atomic_files.h"
#include "morphex/error.h"
#include "morphex/internal/files.h"

namespace morphex {

namespace fs = std::filesystem;

namespace {
// Temporary files of writes in progress, in fixed slots so that a signal handler can unlink them
// without locks or allocation.
constexpr int kSlots = 64;
char pending_paths[kSlots][4096];
std::atomic<bool> pending_used[kSlots];

struct PendingTemporary {
  int slot = -1;
  explicit PendingTemporary(const std::string& path) {
    if (path.size() >= sizeof pending_paths[0]) return;
    for (int i = 0; i < kSlots; ++i) {
      bool expected = false;
      if (pending_used[i].compare_exchange_strong(expected, true)) {
        std::memcpy(pending_paths[i], path.c_str(), path.size() + 1);
        slot = i;
        return;
      }
    }
  }
  ~PendingTemporary() {
    if (slot >= 0) pending_used[slot] = false;
  }
};
// The process's file mode creation mask, read once: from /proc (setting and restoring it with
// umask() would briefly change it for every thread).
mode_t process_umask() {
  static const mode_t mask = [] {
    std::ifstream status("/proc/self/status");
    for (std::string line; std::getline(status, line);)
      if (line.rfind("Umask:", 0) == 0) return mode_t(std::stoul(line.substr(6), nullptr, 8));
    const mode_t old = umask(022);
    umask(old);
    return old;
  }();
  return mask;
}

}  // namespace

void remove_pending_temporary_files() noexcept {
  for (int i = 0; i < kSlots; ++i)
    if (pending_used[i]) unlink(pending_paths[i]);
}

void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& writer) {
  struct stat existing {};
  if (stat(path.c_str(), &existing) == 0 && !S_ISREG(existing.st_mode) &&
      !S_ISDIR(existing.st_mode)) {
    // A device or a pipe (/dev/null, /dev/stdout, a FIFO) is written in place: it holds no file
    // to keep whole, and renaming a temporary over it would replace the device itself (run as
    // root, `--stats /dev/null` turned /dev/null into a regular file).
    std::ofstream out(path, std::ios::binary);
    if (!out) throw StorageError(path, std::string("cannot open: ") + std::strerror(errno));
    writer(out);
    out.flush();
    if (!out) throw StorageError(path, "write failed");
    return;
  }
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::string tmp = (dir / ("." + target.filename().string() + ".tmp.XXXXXX")).string();
  const int fd = mkstemp(tmp.data());
  if (fd < 0)
    throw StorageError(path,
                       std::string("cannot create a temporary file: ") + std::strerror(errno));
  close(fd);
  const PendingTemporary pending(tmp);
  try {
    {
      std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
      if (!out) throw StorageError(path, "cannot write");
      writer(out);
      out.flush();
      if (!out) throw StorageError(path, "write failed");
    }
    // mkstemp made the file private; a finished output gets what the umask gives a new file.
    chmod(tmp.c_str(), 0666 & ~process_umask());
    const int sync_fd = open(tmp.c_str(), O_RDONLY);
    if (sync_fd >= 0) {
      fsync(sync_fd);
      close(sync_fd);
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0)
      throw StorageError(path,
                         std::string("cannot rename the temporary file: ") + std::strerror(errno));
  } catch (...) {
    std::remove(tmp.c_str());
    throw;
  }
}

bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
  return fs::weakly_canonical(a, ec) == fs::weakly_canonical(b, ec);
}

}  // namespace morphex
