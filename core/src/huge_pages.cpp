// SPDX-License-Identifier: GPL-3.0-or-later
// Transparent huge pages for glibc's malloc (morphex/internal/huge_pages.h).
#include "morphex/internal/huge_pages.h"

#include <unistd.h>

#include <cstdlib>
#include <fstream>

namespace morphex {

namespace {
constexpr const char* kTunable = "glibc.malloc.hugetlb";
// With huge pages, where the memory comes from: blocks up to 32 MiB from the heap (whose pages
// are huge) instead of mappings of their own (faulted in 4 KiB at a time, and again for each new
// block once freed), and the heap grown 16 MiB at a time (and as much kept when it shrinks).
// A fresh process faults far less: `morphex bool` of bunny00 and armadillo 6,700 -> 1,700 page
// faults and 0.19 -> 0.12 s, `morphex check bunny00.off` 0.082 -> 0.069 s, for 0-4% more peak
// memory (docs/benchmarks.md). Each only when the user's tunables do not name it.
constexpr const char* kSizes[] = {"glibc.malloc.mmap_threshold=33554432",
                                  "glibc.malloc.top_pad=16777216"};
// Set in the restarted process: it never restarts again, whatever glibc left of its tunables.
constexpr const char* kRestarted = "MORPHEX_RESTARTED_FOR_HUGE_PAGES";
}  // namespace

std::optional<std::string> huge_page_tunables(const char* current, const std::string& thp_mode) {
  if (thp_mode.find("[madvise]") == std::string::npos) return std::nullopt;
  const std::string tunables = current ? current : "";
  // Tunables are name=value pairs joined by ':'; any mention of ours is the user's choice.
  if (tunables.find(kTunable) != std::string::npos) return std::nullopt;
  std::string out =
      tunables.empty() ? std::string(kTunable) + "=1" : tunables + ":" + kTunable + "=1";
  for (const std::string size : kSizes)
    if (tunables.find(size.substr(0, size.find('=') + 1)) == std::string::npos) out += ":" + size;
  return out;
}

namespace detail {

void restart_with_huge_pages(char** argv) {
  if (std::getenv(kRestarted)) return;
  std::string mode;
  std::getline(std::ifstream("/sys/kernel/mm/transparent_hugepage/enabled"), mode);
  const char* current = std::getenv("GLIBC_TUNABLES");
  const std::optional<std::string> tunables = huge_page_tunables(current, mode);
  if (!tunables) return;
  const bool was_set = current != nullptr;
  const std::string before = was_set ? current : "";
  if (setenv("GLIBC_TUNABLES", tunables->c_str(), 1) == 0 && setenv(kRestarted, "1", 1) == 0)
    execv("/proc/self/exe", argv);
  // Still here: no /proc, the binary is gone, or no room in the environment. Run as started.
  unsetenv(kRestarted);
  if (was_set)
    setenv("GLIBC_TUNABLES", before.c_str(), 1);
  else
    unsetenv("GLIBC_TUNABLES");
}

}  // namespace detail
}  // namespace morphex
