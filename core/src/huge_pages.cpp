// SPDX-License-Identifier: GPL-3.0-or-later
// Transparent huge pages for glibc's malloc (morphex/internal/huge_pages.h).
#include "morphex/internal/huge_pages.h"

#include <unistd.h>

#include <cstdlib>
#include <fstream>

namespace morphex {

namespace {
constexpr const char* kTunable = "glibc.malloc.hugetlb";
// Set in the restarted process: it never restarts again, whatever glibc left of its tunables.
constexpr const char* kRestarted = "MORPHEX_RESTARTED_FOR_HUGE_PAGES";
}  // namespace

std::optional<std::string> huge_page_tunables(const char* current, const std::string& thp_mode) {
  if (thp_mode.find("[madvise]") == std::string::npos) return std::nullopt;
  const std::string tunables = current ? current : "";
  // Tunables are name=value pairs joined by ':'; any mention of ours is the user's choice.
  if (tunables.find(kTunable) != std::string::npos) return std::nullopt;
  return tunables.empty() ? std::string(kTunable) + "=1" : tunables + ":" + kTunable + "=1";
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
