// SPDX-License-Identifier: GPL-3.0-or-later
// The table of descriptor settings and their checks (morphex/descriptor_settings.h).
#include "morphex/descriptor_settings.h"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "morphex/error.h"

namespace morphex {
namespace {

using S = DescriptorSettings;

DescriptorSettingInfo integer(const char* name, DescriptorSettingInfo::Field field, double min,
                              double max, const char* doc) {
  return {name, field, min, max, false, doc};
}
DescriptorSettingInfo positive(const char* name, double S::*field, const char* doc) {
  return {name, field, 0, 0, true, doc};
}
DescriptorSettingInfo flag(const char* name, bool S::*field, const char* doc) {
  return {name, field, 0, 0, false, doc};
}

// A number for messages as it was written: 64, 4294967295, 0.05.
std::string text(double value) {
  if (value == std::floor(value) && std::abs(value) < 1e15)
    return std::to_string(static_cast<long long>(value));
  std::ostringstream out;
  out << std::setprecision(15) << value;
  return out.str();
}

}  // namespace

const std::vector<DescriptorSettingInfo>& descriptor_settings_table() {
  // The ranges keep every setting meaningful and the work bounded: 64 scales of exact filters
  // already take hours on a large mesh, and the seed is stored as JSON, which holds integers up
  // to 2^53 exactly (2^32 - 1 is what every front end accepted so far).
  static const std::vector<DescriptorSettingInfo> table = {
      integer("scales", &S::scales, 1, 64, "number of opening (and closing) radii"),
      positive("open_from", &S::open_from,
               "smallest opening cube half side, in units of the thickness T = 3 volume / area"),
      positive("open_to", &S::open_to, "largest opening cube half side, in units of T"),
      positive("close_from", &S::close_from,
               "smallest closing cube half side, in units of L = cbrt(volume)"),
      positive("close_to", &S::close_to, "largest closing cube half side, in units of L"),
      flag("closings", &S::closings, "compute the anti-granulometry (closings)"),
      flag("pose", &S::normalise_pose, "normalise the pose (principal axes) first"),
      integer("facet_budget", &S::facet_budget, 0, 1e9,
              "filter a simplified valid copy of about this many facets (0: the mesh itself)"),
      integer("d2_samples", &S::d2_samples, 16, 1e7, "D2 point pairs"),
      integer("d2_bins", &S::d2_bins, 4, 4096, "D2 histogram bins"),
      integer("seed", &S::seed, 0, 4294967295.0, "D2 random seed")};
  return table;
}

const DescriptorSettingInfo* find_descriptor_setting(const std::string& name) {
  for (const DescriptorSettingInfo& info : descriptor_settings_table())
    if (name == info.name) return &info;
  return nullptr;
}

DescriptorSettingInfo::Type DescriptorSettingInfo::type() const {
  if (std::holds_alternative<bool S::*>(field)) return Type::Bool;
  if (std::holds_alternative<double S::*>(field)) return Type::Number;
  return Type::Integer;
}

nlohmann::json DescriptorSettingInfo::value(const DescriptorSettings& s) const {
  return std::visit([&](auto member) { return nlohmann::json(s.*member); }, field);
}

std::string DescriptorSettingInfo::range_problem(double value) const {
  switch (type()) {
    case Type::Bool:
      return "";
    case Type::Number:
      if (positive && !(value > 0)) return "expected a positive number, got " + text(value);
      if (!positive && !(value >= min && value <= max))
        return "expected a number from " + text(min) + " to " + text(max) + ", got " + text(value);
      return "";
    case Type::Integer:
      if (!(value >= min && value <= max))
        return "expected an integer from " + text(min) + " to " + text(max) + ", got " +
               text(value);
      return "";
  }
  return "";
}

void DescriptorSettingInfo::set(DescriptorSettings& s, const nlohmann::json& value) const {
  const auto refuse = [&](const std::string& what) {
    throw InputError(name, "expected " + what + ", got " + value.dump());
  };
  switch (type()) {
    case Type::Bool:
      if (!value.is_boolean()) refuse("true or false");
      s.*std::get<bool S::*>(field) = value.get<bool>();
      return;
    case Type::Number:
      if (!value.is_number()) refuse(positive ? "a positive number" : "a number");
      break;
    case Type::Integer:
      if (!value.is_number_integer()) refuse("an integer");
      break;
  }
  // Integers are compared as doubles: the ranges are far inside what a double holds exactly, and
  // a larger value is refused whatever its rounding.
  const double x = value.get<double>();
  const std::string problem = range_problem(x);
  if (!problem.empty()) throw InputError(name, problem);
  std::visit(
      [&](auto member) {
        using T = std::remove_reference_t<decltype(s.*member)>;
        if constexpr (std::is_same_v<T, double>)
          s.*member = x;
        else if constexpr (std::is_same_v<T, bool>)
          s.*member = value.get<bool>();
        else if constexpr (std::is_signed_v<T>)
          s.*member = T(value.get<std::int64_t>());
        else
          s.*member = T(value.get<std::uint64_t>());
      },
      field);
}

void check_descriptor_settings(const DescriptorSettings& s) {
  for (const DescriptorSettingInfo& info : descriptor_settings_table()) {
    if (info.type() == DescriptorSettingInfo::Type::Bool) continue;
    const double x = info.value(s).get<double>();
    const std::string problem = info.range_problem(x);
    if (!problem.empty()) throw InputError(info.name, problem);
  }
  // The radii grow from the first to the last (a single scale uses the first).
  if (s.open_from > s.open_to)
    throw InputError("open_from",
                     "open_from/close_from must not exceed open_to/close_to (open_from " +
                         text(s.open_from) + " > open_to " + text(s.open_to) + ")");
  if (s.close_from > s.close_to)
    throw InputError("close_from",
                     "open_from/close_from must not exceed open_to/close_to (close_from " +
                         text(s.close_from) + " > close_to " + text(s.close_to) + ")");
}

void to_json(nlohmann::json& j, const DescriptorSettings& s) {
  j = nlohmann::json::object();
  for (const DescriptorSettingInfo& info : descriptor_settings_table())
    j[info.name] = info.value(s);
}

void from_json(const nlohmann::json& j, DescriptorSettings& s) {
  if (!j.is_object())
    throw InputError("descriptor settings", "expected an object, got " + j.dump());
  for (const auto& [name, value] : j.items()) {
    const DescriptorSettingInfo* info = find_descriptor_setting(name);
    if (!info) throw InputError(name, "not a descriptor setting");
    info->set(s, value);
  }
  check_descriptor_settings(s);
}

}  // namespace morphex
