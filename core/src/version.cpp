// SPDX-License-Identifier: GPL-3.0-or-later
// The library's version, from the CMake project. Alone in its file: the definition it needs is
// given to this file only, so the precompiled header the other sources share stays valid.
#include "morphex/version.h"

const char* morphex::version() {
  return MORPHEX_VERSION;
}
