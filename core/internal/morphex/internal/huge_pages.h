// SPDX-License-Identifier: GPL-3.0-or-later
// Transparent huge pages for glibc's malloc in morphex's executables.
//
// A one-shot command touches all of its memory for the first time: reading bunny00 (75,408
// facets) and checking it faults in about 13,000 pages of 4 KiB, and on the virtual machines
// the project runs on each fault costs over 10 us, more than the check's own work. Where the
// kernel gives huge pages only to memory that asks for them (transparent_hugepage "madvise", the
// common default), glibc's malloc asks for them under its tunable glibc.malloc.hugetlb=1 (glibc
// 2.35 and later). Tunables are read once, when the process starts, so the executable restarts
// itself with the tunable set, before it has done anything. A user's own glibc.malloc.hugetlb
// (0 to keep 4 KiB pages) is left alone.
#pragma once

#include <optional>
#include <string>

namespace morphex {

// The value GLIBC_TUNABLES should take for huge pages, given its current value (`current`, null
// when unset) and the kernel's mode (the line of /sys/kernel/mm/transparent_hugepage/enabled,
// e.g. "always [madvise] never"); nullopt when the process should stay as it is: the mode is not
// "madvise" ("always" gives malloc huge pages unasked, "never" none), or the tunables already say
// what glibc.malloc.hugetlb is. Other tunables are kept; glibc.malloc.mmap_threshold and
// glibc.malloc.top_pad are added unless named, so that large blocks come from the huge-paged heap
// (huge_pages.cpp says why and by how much).
std::optional<std::string> huge_page_tunables(const char* current, const std::string& thp_mode);

namespace detail {
// Replaces the process with itself (/proc/self/exe, the same arguments) under the tunables
// huge_page_tunables gives; returns, changing nothing, when they give none or the exec fails.
void restart_with_huge_pages(char** argv);
}  // namespace detail

// The first call in main of an executable that allocates with glibc's malloc
// (MORPHEX_HUGE_PAGE_MALLOC, set by CMake's morphex_use_malloc: not under TBB's scalable
// allocator, sanitizers or libFuzzer, which bring their own).
inline void use_huge_page_malloc([[maybe_unused]] char** argv) {
#ifdef MORPHEX_HUGE_PAGE_MALLOC
  detail::restart_with_huge_pages(argv);
#endif
}

}  // namespace morphex
