// SPDX-License-Identifier: GPL-3.0-or-later
#include "morphex/internal/modules.h"

#include <dlfcn.h>

#include <filesystem>
#include <system_error>
#include <vector>

#ifndef MORPHEX_MODULE_SUBDIR
#define MORPHEX_MODULE_SUBDIR "lib/morphex"
#endif

namespace morphex {

namespace fs = std::filesystem;

namespace {

// Where modules may be, in order: the executable's folder, the installed layout beside it (an
// installed tree moved elsewhere), then where this build installs them (a program of the
// library's users, wherever it lives).
std::vector<fs::path> module_folders() {
  std::vector<fs::path> folders;
  std::error_code error;
  const fs::path exe = fs::read_symlink("/proc/self/exe", error);
  if (!error) {
    folders.push_back(exe.parent_path());
    folders.push_back(exe.parent_path().parent_path() / MORPHEX_MODULE_SUBDIR);
  }
#ifdef MORPHEX_MODULE_INSTALL_DIR
  folders.emplace_back(MORPHEX_MODULE_INSTALL_DIR);
#endif
  return folders;
}

}  // namespace

LoadedModule open_module(const std::string& file, bool global) {
  LoadedModule module;
  std::string tried;
  for (const fs::path& dir : module_folders()) {
    const fs::path path = dir / file;
    std::error_code error;
    if (!fs::exists(path, error)) {
      tried += (tried.empty() ? "" : ", ") + dir.string();
      continue;
    }
    module.handle = dlopen(path.c_str(), RTLD_NOW | (global ? RTLD_GLOBAL : RTLD_LOCAL));
    if (module.handle) return module;
    const char* why = dlerror();
    module.error = "cannot load " + path.string() + (why ? std::string(": ") + why : "");
    return module;
  }
  module.error = "not found (looked in " + (tried.empty() ? std::string("no folder") : tried) +
                 "): this morphex was not installed whole";
  return module;
}

void* module_symbol(const LoadedModule& module, const char* name) {
  return module.handle ? dlsym(module.handle, name) : nullptr;
}

}  // namespace morphex
