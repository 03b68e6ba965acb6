// SPDX-License-Identifier: GPL-3.0-or-later
// Loadable modules of this build (morphex_*.so): parts of the command line whose libraries are
// heavy to load and that only one command needs (`serve`'s HTTP server, `index`'s MPI). They are
// opened when that command runs, so that every other command starts without them.
//
// A module is looked for beside the running executable (the build tree puts it there), then in
// the installed module folder relative to it (bin/../lib/.../morphex), then in the one this build
// installs to.
#pragma once

#include <string>

#include "morphex/error.h"

namespace morphex {

// A module that cannot be found or loaded: where is its file name, the problem where it was looked
// for or what the loader said. The installation is at fault, not the input (exit code 1).
class ModuleError : public StorageError {
 public:
  using StorageError::StorageError;
};

struct LoadedModule {
  void* handle = nullptr;  // dlopen's, never closed: a module stays until the process exits
  std::string error;       // why it could not be opened, naming where it was looked for
};

// Opens the module `file` (e.g. "morphex_serve_http.so"). `global`: its libraries' symbols are
// made available to libraries they load in turn (Open MPI's plugins need it).
LoadedModule open_module(const std::string& file, bool global);

// The symbol `name` of an open module, or nullptr.
void* module_symbol(const LoadedModule& module, const char* name);

}  // namespace morphex
