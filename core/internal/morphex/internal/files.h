// SPDX-License-Identifier: GPL-3.0-or-later
// Output files as every morphex library writes them (not installed: the libraries' own helper).
#pragma once

#include <functional>
#include <iosfwd>
#include <string>

namespace morphex {

// Writes through `writer` into a temporary file next to `path`, then renames it over `path`:
// readers never see a half-written file and a failure leaves the old file untouched. Throws
// StorageError when the file cannot be created or written.
void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& writer);

// True when both paths name the same file (existing or not).
bool same_file(const std::string& a, const std::string& b);

}  // namespace morphex
