// SPDX-License-Identifier: GPL-3.0-or-later
// Pipeline validation: every problem found before anything runs, each with its JSON location.
#include <algorithm>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>

#include "morphex/internal/files.h"
#include "morphex/io.h"
#include "morphex/pipeline.h"
#include "pipeline_internal.h"

namespace morphex::pipeline {

namespace {

std::string join(const std::vector<Problem>& problems) {
  std::string out;
  for (const Problem& p : problems) out += (out.empty() ? "" : "\n") + p.text();
  return out;
}

std::string at(const std::string& base, const std::string& key) {
  return base + "." + key;
}
std::string at(const std::string& base, std::size_t index) {
  return base + "[" + std::to_string(index) + "]";
}

// Replaces ${name} in every string of `value`; unknown names are problems, deferred ones stay.
void substitute(nlohmann::json& value, const std::string& location, const Variables& variables,
                const std::vector<std::string>& deferred, std::vector<Problem>& problems) {
  if (value.is_object()) {
    for (auto& [key, member] : value.items())
      substitute(member, at(location, key), variables, deferred, problems);
  } else if (value.is_array()) {
    for (std::size_t i = 0; i < value.size(); ++i)
      substitute(value[i], at(location, i), variables, deferred, problems);
  } else if (value.is_string()) {
    const std::string text = value.get<std::string>();
    std::string out;
    std::size_t pos = 0;
    while (pos < text.size()) {
      const std::size_t open = text.find("${", pos);
      if (open == std::string::npos) break;
      const std::size_t close = text.find('}', open);
      if (close == std::string::npos) {
        problems.push_back({location, "unterminated variable in \"" + text + "\""});
        return;
      }
      const std::string name = text.substr(open + 2, close - open - 2);
      out += text.substr(pos, open - pos);
      const auto it = variables.find(name);
      if (it != variables.end())
        out += it->second;
      else
        out += text.substr(open, close - open + 1);  // kept, so that no second error follows
      if (it == variables.end() &&
          std::find(deferred.begin(), deferred.end(), name) == deferred.end())
        problems.push_back(
            {location, "unknown variable ${" + name + "} (set it with --set " + name + "=VALUE)"});
      pos = close + 1;
    }
    value = out + text.substr(std::min(pos, text.size()));
  }
}

// Checks one option's value against its type. A structuring element is built here (returned, so
// that the stage does not build it again); other types return nullptr.
std::shared_ptr<const StructuringElement> check_option(const OptionInfo& option,
                                                       const nlohmann::json& value,
                                                       const std::string& location,
                                                       std::vector<Problem>& problems) {
  auto expected = [&](const std::string& what) {
    problems.push_back({location, "expected " + what + ", got " + value.dump()});
    return nullptr;
  };
  switch (option.type) {
    case OptionType::String:
    case OptionType::Path:
      if (!value.is_string() ||
          (option.type == OptionType::Path && value.get<std::string>().empty()))
        return expected(option.type == OptionType::Path ? "a file path" : "a string");
      if (!option.choices.empty() && std::find(option.choices.begin(), option.choices.end(),
                                               value.get<std::string>()) == option.choices.end()) {
        std::string list;
        for (const auto& c : option.choices) list += (list.empty() ? "" : ", ") + c;
        return expected("one of " + list);
      }
      return nullptr;
    case OptionType::Bool:
      if (!value.is_boolean()) expected("true or false");
      return nullptr;
    case OptionType::Integer:
      if (!value.is_number_integer()) return expected("an integer");
      if ((option.min && value.get<double>() < *option.min) ||
          (option.max && value.get<double>() > *option.max))
        expected("an integer from " + std::to_string(long(*option.min)) + " to " +
                 std::to_string(long(*option.max)));
      return nullptr;
    case OptionType::Number: {
      FT x;
      try {
        x = detail::exact_number(value);
      } catch (const std::exception&) {
        return expected(option.positive ? "a positive number" : "a number");
      }
      if (option.positive && x <= 0) return expected("a positive number");
      return nullptr;
    }
    case OptionType::NumberList: {
      if (!value.is_array() || value.empty()) return expected("a non-empty array of numbers");
      FT previous = 0;
      for (std::size_t i = 0; i < value.size(); ++i) {
        try {
          const FT x = detail::exact_number(value[i]);
          if (x <= previous)
            problems.push_back({at(location, i),
                                "expected a positive number larger than the one "
                                "before, got " +
                                    value[i].dump()});
          previous = x;
        } catch (const std::exception&) {
          problems.push_back({at(location, i), "expected a number, got " + value[i].dump()});
        }
      }
      return nullptr;
    }
    case OptionType::Vector3:
      if (!value.is_array() || value.size() != 3) return expected("an array of 3 numbers");
      for (std::size_t i = 0; i < 3; ++i) {
        try {
          detail::exact_number(value[i]);
        } catch (const std::exception&) {
          problems.push_back({at(location, i), "expected a number, got " + value[i].dump()});
        }
      }
      return nullptr;
    case OptionType::StructuringElement:
      try {
        return std::make_shared<const StructuringElement>(detail::structuring_element(value));
      } catch (const StructuringElementError& e) {
        problems.push_back(
            {value.is_object() && !e.key().empty() ? at(location, e.key()) : location,
             e.problem()});
      } catch (const std::exception& e) {  // an unreadable mesh:path=FILE
        problems.push_back({value.is_object() ? at(location, "path") : location, e.what()});
      }
      return nullptr;
  }
  return nullptr;
}

// The 1-based offset of the first bracket nested deeper than kMaxJsonDepth, outside strings;
// 0 when there is none.
std::size_t too_deep(const std::string& text) {
  std::size_t depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth) return i + 1;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return 0;
}

}  // namespace

PipelineError::PipelineError(std::vector<Problem> problems)
    : InputError(problems.empty() ? "" : problems[0].location,
                 problems.empty() ? "" : problems[0].message, join(problems)),
      problems_(std::move(problems)) {}

nlohmann::json parse_document(const std::string& text, const std::string& name) {
  // "file:line:column" of a byte offset (1-based, as nlohmann reports it).
  const auto location = [&](std::size_t byte) {
    std::size_t line = 1, column = 1;
    for (std::size_t i = 0; i + 1 < byte && i < text.size(); ++i) {
      if (text[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    return name + ":" + std::to_string(line) + ":" + std::to_string(column);
  };
  const auto message = [](const nlohmann::json::exception& e) {
    std::string what = e.what();
    const auto colon = what.find("] ");  // drop nlohmann's "[json.exception.parse_error.101]"
    if (colon != std::string::npos) what = what.substr(colon + 2);
    if (what.rfind("parse error at ", 0) == 0) what = what.substr(what.find(": ") + 2);
    return "malformed JSON: " + what;
  };
  // The parser is iterative, but the document's destructor, dump() and the validation recurse:
  // thousands of nested brackets (40 KB of them) would overflow the stack. A pipeline needs a
  // handful of levels.
  if (const std::size_t byte = too_deep(text); byte > 0)
    throw PipelineError(std::vector<Problem>{
        {location(byte), "JSON nested deeper than " + std::to_string(kMaxJsonDepth) +
                             " levels (a pipeline needs a few)"}});
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw PipelineError(std::vector<Problem>{{location(e.byte), message(e)}});
  } catch (const nlohmann::json::exception& e) {
    // A number too large for a double ("number overflow parsing '1e999'") carries no position:
    // point at the first occurrence of the token it quotes.
    const std::string what = e.what();
    const auto open = what.find('\''), close = what.rfind('\'');
    std::size_t byte = 0;
    if (open != std::string::npos && close > open) {
      const auto at = text.find(what.substr(open + 1, close - open - 1));
      if (at != std::string::npos) byte = at + 1;
    }
    throw PipelineError(std::vector<Problem>{{byte ? location(byte) : name, message(e)}});
  }
}

Variables parse_assignments(const std::vector<std::string>& assignments) {
  Variables out;
  std::vector<Problem> problems;
  for (const std::string& a : assignments) {
    const auto eq = a.find('=');
    if (eq == std::string::npos || eq == 0 || a.find_first_of("${}") < eq)
      problems.push_back({"--set " + a, "expected name=value"});
    else
      out[a.substr(0, eq)] = a.substr(eq + 1);
  }
  if (!problems.empty()) throw PipelineError(std::move(problems));
  return out;
}

void check_assignments_used(const nlohmann::json& document, const Variables& assignments) {
  const std::string text = document.dump();
  std::vector<Problem> problems;
  for (const auto& [name, value] : assignments)
    if (text.find("${" + name + "}") == std::string::npos)
      problems.push_back({"--set " + name, "the pipeline uses no ${" + name + "}"});
  if (!problems.empty()) throw PipelineError(std::move(problems));
}

nlohmann::json load_document(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw PipelineError(std::vector<Problem>{{path, "cannot open the pipeline file"}});
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_document(buffer.str(), path);
}

namespace {

// The stages array, and the variables bound: --set first, then the document's defaults.
nlohmann::json stages_and_variables(const nlohmann::json& document, Variables& bound,
                                    std::vector<Problem>& problems) {
  if (document.is_array()) return document;
  if (!document.is_object() || !document.contains("pipeline")) return nullptr;
  for (const auto& [key, value] : document.items()) {
    if (key == "variables") {
      if (!value.is_object()) {
        problems.push_back({key, "expected an object of default values, got " + value.dump()});
        continue;
      }
      for (const auto& [name, default_value] : value.items()) {
        if (default_value.is_string())
          bound.emplace(name, default_value.get<std::string>());
        else if (default_value.is_number())
          bound.emplace(name, default_value.dump());
        else
          problems.push_back(
              {"variables." + name, "expected a string or a number, got " + default_value.dump()});
      }
    } else if (key != "pipeline" && key != "description") {
      problems.push_back({key,
                          "unknown top-level key (expected \"pipeline\", and optionally "
                          "\"description\" and \"variables\")"});
    }
  }
  return document["pipeline"];
}

// The stage's options checked against its registered ones, defaults filled in.
void check_options(Stage& stage, const nlohmann::json& raw, const std::string& here,
                   std::vector<Problem>& problems) {
  const std::vector<OptionInfo>& options = stage.info->options;
  for (const auto& item : raw.items()) {
    const std::string& key = item.key();
    if (key == "type" || key == "tag" || key == "inputs") continue;
    const auto option = std::find_if(options.begin(), options.end(),
                                     [&](const OptionInfo& o) { return o.name == key; });
    if (option == options.end()) {
      std::string known;
      for (const auto& o : options) known += (known.empty() ? "" : ", ") + o.name;
      problems.push_back(
          {at(here, key), "unknown option for '" + stage.type + "' (" +
                              (known.empty() ? "it takes no options" : "known: " + known) + ")"});
      continue;
    }
    if (auto element = check_option(*option, item.value(), at(here, key), problems))
      stage.elements[key] = std::move(element);
    stage.options[key] = item.value();
  }
  for (const OptionInfo& option : options) {
    if (stage.options.contains(option.name)) continue;
    if (option.default_value) {
      stage.options[option.name] = *option.default_value;
      if (option.type == OptionType::StructuringElement)
        stage.elements[option.name] =
            check_option(option, *option.default_value, at(here, option.name), problems);
    } else
      problems.push_back({at(here, option.name), "missing (required by '" + stage.type + "')"});
  }
}

// What the stages' "inputs" name, by tag, as the raw document gives them.
struct StageGraph {
  std::map<std::string, std::size_t> tag_index;
  std::vector<std::vector<std::string>> input_tags;
};

// One stage of the array: type, tag, input tags and options (variables substituted).
Stage parse_stage(nlohmann::json raw, std::size_t i, const Variables& bound,
                  const std::vector<std::string>& deferred, const StageRegistry& registry,
                  StageGraph& graph, std::vector<Problem>& problems) {
  const std::string here = at("pipeline", i);
  Stage stage;
  stage.index = i;
  if (!raw.is_object()) {
    problems.push_back({here, "expected a stage object with a \"type\""});
    return stage;
  }
  substitute(raw, here, bound, deferred, problems);
  if (!raw.contains("type") || !raw["type"].is_string()) {
    problems.push_back({at(here, "type"), "missing (a stage type such as \"read\")"});
  } else {
    stage.type = raw["type"].get<std::string>();
    stage.info = registry.find(stage.type);
    if (!stage.info)
      problems.push_back({at(here, "type"), "unknown stage '" + stage.type + "' (did you mean '" +
                                                registry.closest(stage.type) + "'?)"});
  }
  stage.tag = stage.type + "#" + std::to_string(i);
  if (raw.contains("tag")) {
    if (!raw["tag"].is_string() || raw["tag"].get<std::string>().empty()) {
      problems.push_back(
          {at(here, "tag"), "expected a non-empty string, got " + raw["tag"].dump()});
    } else {
      stage.tag = raw["tag"].get<std::string>();
      const auto [it, inserted] = graph.tag_index.emplace(stage.tag, i);
      if (!inserted)
        problems.push_back({at(here, "tag"), "duplicate tag '" + stage.tag + "' (first used by " +
                                                 at("pipeline", it->second) + ")"});
    }
  }
  if (raw.contains("inputs")) {
    const auto& inputs = raw["inputs"];
    if (inputs.is_string())
      graph.input_tags[i].push_back(inputs.get<std::string>());
    else if (inputs.is_array() &&
             std::all_of(inputs.begin(), inputs.end(), [](const auto& t) { return t.is_string(); }))
      for (const auto& t : inputs) graph.input_tags[i].push_back(t.get<std::string>());
    else
      problems.push_back(
          {at(here, "inputs"), "expected a tag or an array of tags, got " + inputs.dump()});
  }
  if (stage.info) check_options(stage, raw, here, problems);
  return stage;
}

// Inputs: explicit tags, or the previous stage for one-input stages.
void resolve_inputs(Pipeline& pipeline, const StageGraph& graph, std::vector<Problem>& problems) {
  for (std::size_t i = 0; i < pipeline.stages.size(); ++i) {
    Stage& stage = pipeline.stages[i];
    if (!stage.info) continue;
    const std::string here = at("pipeline", i);
    const std::vector<std::string>& tags = graph.input_tags[i];
    const int wanted = stage.info->inputs;
    if (tags.empty()) {
      if (wanted == 1 && i > 0)
        stage.inputs.push_back(i - 1);
      else if (wanted > 0)
        problems.push_back(
            {at(here, "inputs"), wanted == 1
                                     ? "'" + stage.type + "' needs an input: it cannot come first"
                                     : "'" + stage.type + "' needs \"inputs\" with 2 tags"});
      continue;
    }
    if (int(tags.size()) != wanted) {
      problems.push_back({at(here, "inputs"),
                          "'" + stage.type + "' takes " + std::to_string(wanted) + " input" +
                              (wanted == 1 ? "" : "s") + ", got " + std::to_string(tags.size())});
      continue;
    }
    for (std::size_t k = 0; k < tags.size(); ++k) {
      const auto it = graph.tag_index.find(tags[k]);
      if (it == graph.tag_index.end())
        problems.push_back({at(at(here, "inputs"), k), "unknown tag '" + tags[k] + "'"});
      else
        stage.inputs.push_back(it->second);
    }
  }
}

// A topological order of the stage graph (depth first); a cycle is reported with its tags.
void order_stages(Pipeline& pipeline, std::vector<Problem>& problems) {
  std::vector<int> state(pipeline.stages.size(), 0);  // 0 new, 1 on the path, 2 done
  std::vector<std::size_t> path;
  bool cyclic = false;
  std::function<void(std::size_t)> visit = [&](std::size_t s) {
    if (cyclic || state[s] == 2) return;
    if (state[s] == 1) {
      std::string cycle;
      const auto from = std::find(path.begin(), path.end(), s);
      for (auto it = from; it != path.end(); ++it) cycle += pipeline.stages[*it].tag + " -> ";
      problems.push_back(
          {at(at("pipeline", s), "inputs"), "cycle: " + cycle + pipeline.stages[s].tag});
      cyclic = true;
      return;
    }
    state[s] = 1;
    path.push_back(s);
    for (std::size_t input : pipeline.stages[s].inputs) visit(input);
    path.pop_back();
    state[s] = 2;
    pipeline.order.push_back(s);
  };
  for (std::size_t s = 0; s < pipeline.stages.size(); ++s) visit(s);
}

// The file of a mesh structuring element option ({"shape": "mesh", "path": F} or "mesh:path=F").
std::string element_file(const nlohmann::json& value) {
  if (value.is_object() && value.value("shape", "") == "mesh" && value.contains("path") &&
      value["path"].is_string())
    return value["path"].get<std::string>();
  if (!value.is_string()) return "";
  const std::string text = value.get<std::string>();
  const std::size_t start = text.find("path=");
  if (text.rfind("mesh:", 0) != 0 || start == std::string::npos) return "";
  const std::size_t end = text.find(',', start);
  return text.substr(start + 5, end == std::string::npos ? std::string::npos : end - start - 5);
}

}  // namespace

std::vector<FileUse> files_read(const Pipeline& pipeline) {
  std::vector<FileUse> out;
  for (const Stage& s : pipeline.stages) {
    if (s.type == "read" && s.options.contains("path") && s.options["path"].is_string())
      out.push_back({s.options["path"].get<std::string>(), at(at("pipeline", s.index), "path"),
                     "the input read by " + at("pipeline", s.index)});
    for (const auto& [name, element] : s.elements)
      if (const std::string file = element_file(s.options.value(name, nlohmann::json()));
          !file.empty())
        out.push_back({file, at(at("pipeline", s.index), name),
                       "the structuring element of " + at(at("pipeline", s.index), name)});
  }
  return out;
}

std::vector<FileUse> files_written(const Pipeline& pipeline) {
  std::vector<FileUse> out;
  for (const Stage& s : pipeline.stages)
    if (s.type == "write" && s.options.contains("path") && s.options["path"].is_string())
      out.push_back({s.options["path"].get<std::string>(), at(at("pipeline", s.index), "path"),
                     "the output of " + at("pipeline", s.index)});
  return out;
}

namespace {

// A read feeding only repair or solidify stages passes its mesh on unchecked.
void mark_unchecked_reads(Pipeline& pipeline) {
  for (Stage& r : pipeline.stages) {
    if (r.type != "read") continue;
    bool consumed = false, only_repairs = true;
    for (const Stage& s : pipeline.stages)
      if (std::find(s.inputs.begin(), s.inputs.end(), r.index) != s.inputs.end()) {
        consumed = true;
        only_repairs = only_repairs && (s.type == "repair" || s.type == "solidify");
      }
    r.unchecked = consumed && only_repairs;
  }
}

// No write may replace a file that a read stage or a mesh structuring element takes as input.
void check_overwrites(const Pipeline& pipeline, std::vector<Problem>& problems) {
  const std::vector<FileUse> reads = files_read(pipeline);
  for (const FileUse& w : files_written(pipeline))
    for (const FileUse& r : reads)
      if (r.path == w.path || same_file(r.path, w.path))
        problems.push_back({w.location, "would overwrite " + r.what + " (" + w.path + ")"});
}

}  // namespace

Pipeline validate(const nlohmann::json& document, const std::string& name,
                  const Variables& variables, const std::vector<std::string>& deferred,
                  const StageRegistry& registry) {
  std::vector<Problem> problems;
  Pipeline pipeline;
  pipeline.name = name;
  pipeline.document = document;
  Variables bound = variables;  // --set wins over the document's defaults
  const nlohmann::json stages = stages_and_variables(document, bound, problems);
  if (!stages.is_array() || stages.empty())
    throw PipelineError(std::vector<Problem>{{"pipeline", "expected a non-empty array of stages"}});
  StageGraph graph;
  graph.input_tags.resize(stages.size());
  for (std::size_t i = 0; i < stages.size(); ++i)
    pipeline.stages.push_back(
        parse_stage(stages[i], i, bound, deferred, registry, graph, problems));
  resolve_inputs(pipeline, graph, problems);
  order_stages(pipeline, problems);
  mark_unchecked_reads(pipeline);
  check_overwrites(pipeline, problems);
  if (!problems.empty()) throw PipelineError(std::move(problems));
  return pipeline;
}

}  // namespace morphex::pipeline
