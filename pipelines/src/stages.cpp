// SPDX-License-Identifier: GPL-3.0-or-later
// The built-in stages: options, limits, defaults and what each one does.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/descriptor_settings.h"
#include "morphex/descriptors.h"
#include "morphex/io.h"
#include "morphex/json.h"
#include "morphex/minkowski.h"
#include "morphex/morph_json.h"
#include "morphex/morphology.h"
#include "morphex/pipeline.h"
#include "morphex/simplify.h"
#include "morphex/solid.h"
#include "morphex/solidify.h"
#include "pipeline_internal.h"

namespace morphex::pipeline {

const char* to_string(OptionType type) {
  switch (type) {
    case OptionType::String:
      return "string";
    case OptionType::Path:
      return "path";
    case OptionType::Bool:
      return "bool";
    case OptionType::Integer:
      return "integer";
    case OptionType::Number:
      return "number";
    case OptionType::NumberList:
      return "[number, ...]";
    case OptionType::Vector3:
      return "[x, y, z]";
    case OptionType::StructuringElement:
      return "structuring element";
  }
  return "?";
}

namespace detail {

FT exact_number(const nlohmann::json& value) {
  if (value.is_number_integer()) return parse_exact_number(value.dump());
  if (value.is_number()) return FT(value.get<double>());  // the JSON text's nearest double
  if (value.is_string()) return parse_exact_number(value.get<std::string>());
  throw InputError("", "not a number");
}

StructuringElement structuring_element(const nlohmann::json& value) {
  if (value.is_string()) return parse_structuring_element(value.get<std::string>());
  if (!value.is_object())
    throw StructuringElementError("", "",
                                  "expected an object such as {\"shape\": \"ball\", \"r\": 0.05}");
  if (!value.contains("shape") || !value["shape"].is_string())
    throw StructuringElementError("", "shape",
                                  "missing (a string: " + structuring_element_shape_list() + ")");
  SeParameters params;
  for (const auto& [key, v] : value.items()) {
    if (key == "shape") continue;
    if (v.is_string())
      params.emplace_back(key, v.get<std::string>());
    else if (v.is_number())
      params.emplace_back(key, v.dump());  // the JSON text: 0.05 stays "0.05"
    else
      throw StructuringElementError(value["shape"].get<std::string>(), key,
                                    "expected a number or a string, got " + v.dump());
  }
  return make_structuring_element(value["shape"].get<std::string>(), params);
}

Transformation rotation(const std::string& axis, const FT& degrees) {
  const int index = axis == "x" ? 0 : axis == "y" ? 1 : 2;
  FT c, s;
  const double d = CGAL::to_double(degrees);
  const double turns = d / 90.0;
  if (FT(double(std::llround(turns))) * 90 == degrees) {
    const long q = ((std::llround(turns) % 4) + 4) % 4;
    c = q == 0 ? 1 : q == 2 ? -1 : 0;
    s = q == 1 ? 1 : q == 3 ? -1 : 0;
    return axis_rotation(index, c, s);
  }
  return half_tangent_rotation(index,
                               FT(std::round(std::tan(d * M_PI / 360.0) * 1e9)) / FT(1000000000));
}

}  // namespace detail

namespace {

OptionInfo required(std::string name, OptionType type, std::string description) {
  OptionInfo o;
  o.name = std::move(name);
  o.type = type;
  o.description = std::move(description);
  return o;
}

OptionInfo optional(std::string name, OptionType type, nlohmann::json value,
                    std::string description) {
  OptionInfo o = required(std::move(name), type, std::move(description));
  o.default_value = std::move(value);
  return o;
}

StageValue boolean_stage(StageContext& c, BooleanOp op) {
  return compute_boolean(c.solid(0), c.solid(1), op).solid;
}

StageValue morphology_stage(StageContext& c, MorphologyOp op) {
  const StructuringElement& se = c.element("se");  // built once, by validation
  MorphologyStats stats;
  Solid result = apply_morphology(op, c.solid(0), se, &stats);
  c.extra["se"] = se.spec;
  c.extra["pieces"] = stats.pieces;
  return StageValue(std::move(result));
}

// The describe stage's options: the table of descriptor settings (morphex/descriptor_settings.h),
// with its names, defaults, ranges and documentation.
std::vector<OptionInfo> describe_options() {
  const DescriptorSettings defaults;
  std::vector<OptionInfo> out;
  for (const DescriptorSettingInfo& setting : descriptor_settings_table()) {
    using Type = DescriptorSettingInfo::Type;
    const Type type = setting.type();
    OptionInfo o = optional(setting.name,
                            type == Type::Bool     ? OptionType::Bool
                            : type == Type::Number ? OptionType::Number
                                                   : OptionType::Integer,
                            setting.value(defaults), setting.doc);
    o.positive = setting.positive;
    if (type != Type::Bool && !setting.positive) {
      o.min = setting.min;
      o.max = setting.max;
    }
    out.push_back(std::move(o));
  }
  return out;
}

OptionInfo repair_budget() {
  OptionInfo budget = optional("budget", OptionType::Number, RepairOptions().budget,
                               "work budget of the exact arrangement per input face (the sum "
                               "over faces of the squared number of faces each meets; 0: no "
                               "bound), so that a hostile soup fails instead of exhausting memory");
  budget.min = 0;
  return budget;
}

// Reading, repairing and writing meshes.
void add_io_stages(StageRegistry& r) {
  r.add(
      {"read",
       "read a closed mesh (OFF, OBJ, STL, PLY, 3MF) and check that it is a valid solid (unless it "
       "goes only to repair stages)",
       0,
       {required("path", OptionType::Path, "mesh file")},
       [](StageContext& c) {
         const std::string path = c.option("path").get<std::string>();
         Mesh mesh = read_mesh(path);
         if (c.stage.unchecked) return StageValue(std::move(mesh));
         const MeshReport report = check_mesh(mesh, kValidityOnly);
         if (!report.valid_solid())
           throw InputError(
               path, describe_problems(report) + " (a repair stage after the read repairs it)");
         return StageValue(check_solid(std::move(mesh), path));
       }});
  r.add({"repair",
         "exact repair: the valid solid a closed mesh bounds where it crosses or touches itself, "
         "repeats vertices or faces, or has faces without area (a valid solid passes unchanged)",
         1,
         {repair_budget()},
         [](StageContext& c) {
           RepairOptions options;
           options.budget = c.option("budget").get<double>();
           RepairResult r = repair_mesh(c.mesh(0), options);
           c.extra["repair"] = r.report;
           return StageValue(std::move(r.solid));
         }});
  r.add(
      {"solidify",
       "the valid solid of a mesh as real collections hold them (soups, open surfaces, flipped, "
       "duplicated or degenerate faces, cracks, overlapping or inward parts); a valid solid "
       "passes unchanged",
       1,
       {optional("weld_tolerance", OptionType::Number, SolidifyOptions().weld_tolerance,
                 "vertices closer than this fraction of the bounding-box diagonal are merged "
                 "(cracks)"),
        optional("fill_holes", OptionType::Bool, true, "close open borders by triangulating them"),
        repair_budget()},
       [](StageContext& c) {
         SolidifyOptions options;
         options.weld_tolerance = c.option("weld_tolerance").get<double>();
         options.fill_holes = c.option("fill_holes").get<bool>();
         options.repair.budget = c.option("budget").get<double>();
         SolidifyResult r = solidify(c.mesh(0), options);
         c.extra["solidify"] = r.report;
         return StageValue(std::move(r.solid));
       }});
  r.add({"write",
         "write the mesh atomically (format from the extension); passes it on",
         1,
         {required("path", OptionType::Path, "output file; missing directories are created"),
          optional("exact", OptionType::Bool, false,
                   "lossless exact OFF (rational coordinates) instead of doubles")},
         [](StageContext& c) {
           const std::string path = c.option("path").get<std::string>();
           const auto parent = std::filesystem::path(path).parent_path();
           if (!parent.empty()) std::filesystem::create_directories(parent);
           WriteOptions options;
           options.exact = c.option("exact").get<bool>();
           options.provenance = "pipeline stage " + c.stage.tag;
           const RoundingReport r = write_mesh(c.solid(0), path, options);
           c.extra["path"] = path;
           // What rounding to the format did (plain formats: the file is a valid solid).
           // The report's keys that say what happened to the file, not where the time went.
           if (!options.exact) {
             const nlohmann::json rounding = r;
             for (const char* key :
                  {"moved_vertices", "rounds", "resolved_pairs", "max_displacement", "collapsed"})
               c.extra["rounding"][key] = rounding.at(key);
           }
           return StageValue(c.solid(0));
         }});
}

// The exact operations: morphology, Booleans, Minkowski sums, and simplification.
void add_operation_stages(StageRegistry& r) {
  const std::pair<MorphologyOp, const char*> morphology[] = {
      {MorphologyOp::Dilate, "dilation A + B"},
      {MorphologyOp::Erode, "erosion {x : x + B inside A}"},
      {MorphologyOp::Open, "opening: erosion then dilation (removes what B cannot fit in)"},
      {MorphologyOp::Close, "closing: dilation then erosion (fills what B cannot enter)"}};
  for (const auto& [op, description] : morphology)
    r.add(
        {to_string(op),
         description,
         1,
         {required("se", OptionType::StructuringElement,
                   "structuring element, {\"shape\": ..., parameters} or \"shape:key=value,...\"")},
         [op = op](StageContext& c) { return morphology_stage(c, op); }});
  for (BooleanOp op : {BooleanOp::Union, BooleanOp::Intersection, BooleanOp::Difference})
    r.add({to_string(op),
           op == BooleanOp::Difference
               ? "exact Boolean difference of two inputs (first minus second)"
               : std::string("exact Boolean ") + to_string(op) + " of two inputs",
           2,
           {},
           [op](StageContext& c) { return boolean_stage(c, op); }});
  r.add({"minkowski", "exact Minkowski sum of two inputs", 2, {}, [](StageContext& c) {
           MinkowskiStats stats;
           Solid sum = minkowski_sum(c.solid(0), c.solid(1), &stats);
           c.extra["pieces"] = stats.pieces;
           return StageValue(std::move(sum));
         }});
  OptionInfo facets = required("facets", OptionType::Integer,
                               "facet budget: the copy has about this many facets, never more "
                               "than the input");
  facets.min = 8;
  facets.max = 1e9;
  r.add({"simplify",
         "a coarser valid solid near the mesh by edge collapse (double precision; the budget is "
         "doubled until the copy is a valid solid)",
         1,
         {facets},
         [](StageContext& c) {
           SimplifyReport report;
           Mesh copy = simplified_solid(to_double(c.solid(0)),
                                        c.option("facets").get<std::size_t>(), &report);
           c.extra["simplified"] = report.simplified;
           c.extra["attempts"] = report.attempts;
           // simplified_solid checks its copy (its contract: a valid solid or InvalidSolid).
           return StageValue(check_solid(std::move(copy), "simplify"));
         }});
}

// Exact rigid motions and scaling.
void add_transform_stages(StageRegistry& r) {
  r.add({"translate",
         "move the mesh by an exact offset",
         1,
         {required("offset", OptionType::Vector3, "[x, y, z]")},
         [](StageContext& c) {
           const auto& v = c.option("offset");
           return StageValue(transformed(
               c.solid(0), Transformation(CGAL::TRANSLATION, Vector(detail::exact_number(v[0]),
                                                                    detail::exact_number(v[1]),
                                                                    detail::exact_number(v[2])))));
         }});
  OptionInfo factor = required("factor", OptionType::Number, "uniform scale factor");
  factor.positive = true;
  r.add({"scale", "scale the mesh about the origin", 1, {factor}, [](StageContext& c) {
           const FT f = detail::exact_number(c.option("factor"));
           return StageValue(transformed(c.solid(0), Transformation(CGAL::SCALING, f)));
         }});
  OptionInfo axis = optional("axis", OptionType::String, "z", "rotation axis: x, y or z");
  axis.choices = {"x", "y", "z"};
  r.add({"rotate",
         "rotate about a coordinate axis through the origin (exactly orthogonal; multiples of 90 "
         "degrees exact, other angles within 1e-9 radian)",
         1,
         {axis, required("degrees", OptionType::Number, "angle, counter-clockwise")},
         [](StageContext& c) {
           return StageValue(transformed(
               c.solid(0), detail::rotation(c.option("axis").get<std::string>(),
                                            detail::exact_number(c.option("degrees")))));
         }});
}

// Stages that report on the mesh and pass it on.
void add_report_stages(StageRegistry& r) {
  r.add({"describe",
         "multi-scale granulometry and anti-granulometry by exact openings and closings with "
         "cubes, where their residues lie, and the D2 baseline; passes the mesh on",
         1, describe_options(), [](StageContext& c) {
           DescriptorSettings settings = descriptor_settings(c.stage);
           settings.on_progress = c.progress;
           const Descriptors d = describe(c.solid(0), settings);
           // The library's JSON of the description (morphex/morph_json.h), its vectors under the
           // name reports and indexes have always read them by, "descriptors".
           c.extra = d;
           c.extra["descriptors"] = std::move(c.extra["vectors"]);
           c.extra.erase("vectors");
           c.extra["descriptor_settings"] = settings.to_string();
           return StageValue(c.solid(0));
         }});
  r.add({"check",
         "report validity, volume, genus and components; passes the mesh on",
         1,
         {optional("require_valid", OptionType::Bool, true,
                   "fail this input when the mesh is not a valid solid")},
         [](StageContext& c) {
           const MeshReport report = check_mesh(c.mesh(0), kValidityOnly);
           c.extra["valid"] = report.valid_solid();
           c.extra["genus"] = report.genus;
           c.extra["components"] = report.components;
           if (c.option("require_valid").get<bool>() && !report.valid_solid())
             throw InvalidSolid("", describe_problems(report));
           return StageValue(c.solid(0));
         }});
}

}  // namespace

DescriptorSettings descriptor_settings(const Stage& stage) {
  // Validation checked each option; the library checks them together (open_from <= open_to),
  // naming the setting. A number option may hold a number's text (from a ${variable}, or a
  // fraction such as "1/20"): its nearest double.
  nlohmann::json options = stage.options;
  for (auto& [name, value] : options.items())
    if (value.is_string()) value = CGAL::to_double(detail::exact_number(value));
  return options.get<DescriptorSettings>();
}

void StageRegistry::add(StageInfo stage) {
  if (find(stage.type)) throw std::logic_error("stage registered twice: " + stage.type);
  stages_.push_back(std::move(stage));
}

const StageInfo* StageRegistry::find(const std::string& type) const {
  for (const StageInfo& s : stages_)
    if (s.type == type) return &s;
  return nullptr;
}

std::string StageRegistry::closest(const std::string& type) const {
  std::string best;
  std::size_t best_distance = std::string::npos;
  for (const StageInfo& s : stages_) {
    // Levenshtein distance, one row at a time.
    std::vector<std::size_t> row(s.type.size() + 1);
    for (std::size_t j = 0; j < row.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= type.size(); ++i) {
      std::size_t diagonal = row[0];
      row[0] = i;
      for (std::size_t j = 1; j <= s.type.size(); ++j) {
        const std::size_t up = row[j];
        row[j] = std::min(
            {row[j] + 1, row[j - 1] + 1, diagonal + (type[i - 1] == s.type[j - 1] ? 0 : 1)});
        diagonal = up;
      }
    }
    if (row.back() < best_distance) {
      best_distance = row.back();
      best = s.type;
    }
  }
  return best;
}

const StageRegistry& StageRegistry::builtin() {
  static const StageRegistry registry = [] {
    StageRegistry r;
    add_io_stages(r);
    add_operation_stages(r);
    add_transform_stages(r);
    add_report_stages(r);
    return r;
  }();
  return registry;
}

}  // namespace morphex::pipeline
