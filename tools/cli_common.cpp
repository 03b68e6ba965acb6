// SPDX-License-Identifier: GPL-3.0-or-later
#include "cli_common.h"

#include <iostream>

#include "morphex/io.h"

namespace morphex::cli {

void print_error(const std::string& message) {
  std::cerr << "morphex: " << message << '\n';
}

void emit_json(const nlohmann::json& value, const std::string& target) {
  if (target == "-") {
    std::cout << value.dump() << std::endl;
    return;
  }
  write_file_atomically(target, [&](std::ostream& out) { out << value.dump(2) << '\n'; });
}

}  // namespace morphex::cli
