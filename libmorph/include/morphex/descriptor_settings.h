// SPDX-License-Identifier: GPL-3.0-or-later
// The descriptor settings as one table: name, type, default, range and documentation of every
// field of DescriptorSettings (morphex/descriptors.h). The command line's `describe` options, the
// describe stage's options, Python's describe() keywords and the web server's reading of stored
// settings are all made from it, and the checks are the library's, done once:
//
//   name           the pipeline option and Python keyword; the command line's option is
//                  --name with '-' for '_' (a Bool is a --no-name flag, since it is on by default)
//   range          [min, max] for Integer and Number; `positive` Numbers exclude 0 and have no max
//
// Errors are InputError whose where() is the setting's name ("scales: expected an integer from 1
// to 64, got 0"), so each front end can show it under its own name for the setting.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "morphex/descriptors.h"

namespace morphex {

struct DescriptorSettingInfo {
  enum class Type { Integer, Number, Bool };
  // The field it reads and writes, typed, so a front end can bind it directly. (std::size_t and
  // std::uint64_t are each one of the two unsigned types, which may be the same.)
  using Field = std::variant<int DescriptorSettings::*, unsigned long DescriptorSettings::*,
                             unsigned long long DescriptorSettings::*, double DescriptorSettings::*,
                             bool DescriptorSettings::*>;
  const char* name;
  Field field;
  double min = 0, max = 0;  // Integer and Number (unused when `positive`)
  bool positive = false;    // Number: strictly greater than zero, unbounded
  const char* doc;          // one line, lower case, saying what the value is (for Bool: when on)

  Type type() const;
  nlohmann::json value(const DescriptorSettings& settings) const;  // the default: of {}
  // Sets the field from JSON, checking type and range; throws InputError(name, problem).
  void set(DescriptorSettings& settings, const nlohmann::json& value) const;
  // Why `value` is out of range ("expected a positive number, got -1"), "" when it is not.
  std::string range_problem(double value) const;
};

// Every setting, in DescriptorSettings' order (on_progress, not a setting, is not in it).
const std::vector<DescriptorSettingInfo>& descriptor_settings_table();
// The entry named `name`, or nullptr.
const DescriptorSettingInfo* find_descriptor_setting(const std::string& name);

// Throws InputError(name, problem) for the first setting out of its range, and for an opening
// (closing) range that is not growing: open_from > open_to, close_from > close_to. describe()
// calls it; front ends call it first to refuse before reading a mesh.
void check_descriptor_settings(const DescriptorSettings& settings);

// {name: value} for every setting of the table.
void to_json(nlohmann::json& j, const DescriptorSettings& settings);
// From {name: value}: names left out keep their defaults; an unknown name, a value of the wrong
// type or out of range throws InputError naming it; then check_descriptor_settings.
void from_json(const nlohmann::json& j, DescriptorSettings& settings);

}  // namespace morphex
