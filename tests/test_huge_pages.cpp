// SPDX-License-Identifier: GPL-3.0-or-later
// The executables' restart for glibc's huge pages (morphex/internal/huge_pages.h): when, and with
// which tunables. The restart itself is tested from outside, on the command line
// (tests/cli/huge_pages.sh).
#include <gtest/gtest.h>

#include <string>

#include "morphex/internal/huge_pages.h"

namespace morphex {
namespace {

const char* const kMadvise = "always [madvise] never";

// Huge pages, and where the memory comes from (the heap, grown in large steps).
const std::string kOurs =
    "glibc.malloc.hugetlb=1:glibc.malloc.mmap_threshold=33554432:glibc.malloc.top_pad=16777216";

TEST(HugePages, AskedForWhereTheKernelGivesThemOnRequest) {
  EXPECT_EQ(huge_page_tunables(nullptr, kMadvise), kOurs);
  EXPECT_EQ(huge_page_tunables("", kMadvise), kOurs);
  // The kernel's line as read, with or without its newline.
  EXPECT_EQ(huge_page_tunables(nullptr, "always [madvise] never\n"), kOurs);
}

TEST(HugePages, OtherTunablesAreKept) {
  EXPECT_EQ(huge_page_tunables("glibc.malloc.arena_max=4", kMadvise),
            "glibc.malloc.arena_max=4:" + kOurs);
  EXPECT_EQ(
      huge_page_tunables("glibc.malloc.arena_max=4:glibc.malloc.trim_threshold=65536", kMadvise),
      "glibc.malloc.arena_max=4:glibc.malloc.trim_threshold=65536:" + kOurs);
  // The user's own sizes stand; ours fill in the others.
  EXPECT_EQ(huge_page_tunables("glibc.malloc.mmap_threshold=1048576", kMadvise),
            "glibc.malloc.mmap_threshold=1048576:glibc.malloc.hugetlb=1:"
            "glibc.malloc.top_pad=16777216");
  EXPECT_EQ(huge_page_tunables("glibc.malloc.top_pad=0", kMadvise),
            "glibc.malloc.top_pad=0:glibc.malloc.hugetlb=1:glibc.malloc.mmap_threshold=33554432");
}

TEST(HugePages, TheUsersChoiceStands) {
  EXPECT_EQ(huge_page_tunables("glibc.malloc.hugetlb=0", kMadvise), std::nullopt);
  EXPECT_EQ(huge_page_tunables("glibc.malloc.arena_max=4:glibc.malloc.hugetlb=2", kMadvise),
            std::nullopt);
}

TEST(HugePages, NothingWhereAskingChangesNothing) {
  // "always": every large enough mapping gets them unasked; "never": none; no THP at all.
  EXPECT_EQ(huge_page_tunables(nullptr, "[always] madvise never"), std::nullopt);
  EXPECT_EQ(huge_page_tunables(nullptr, "always madvise [never]"), std::nullopt);
  EXPECT_EQ(huge_page_tunables(nullptr, ""), std::nullopt);
  EXPECT_EQ(huge_page_tunables("glibc.malloc.arena_max=4", "[always] madvise never"), std::nullopt);
}

}  // namespace
}  // namespace morphex
