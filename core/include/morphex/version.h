// SPDX-License-Identifier: GPL-3.0-or-later
// The version of the morphex libraries, written into the files they make.
#pragma once

namespace morphex {

// "MAJOR.MINOR.PATCH", from the CMake project.
const char* version();

}  // namespace morphex
