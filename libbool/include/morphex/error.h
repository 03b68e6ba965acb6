// SPDX-License-Identifier: GPL-3.0-or-later
// The error model of every morphex library (libbool, libmorph, pipelines, libretrieval).
//
//   morphex::Error                  the input is unusable: a file, a mesh, a number, an option, a
//   |                               structuring element, a pipeline. what() is "<where>: <problem>"
//   |                               where names the file, operand or JSON path ("" when the
//   |                               caller knows it better), problem says what is wrong and where
//   |                               inside (line, vertex, face). Derives from
//   std::invalid_argument, |                               so code that catches that keeps working.
//   +- InputError                   a file or value that cannot be used (readers, parsers, repair)
//   |  +- InvalidSolid              a mesh that is not a valid solid where one is needed
//   +- StructuringElementError      (morphex/structuring_element.h) with the parameter at fault
//   +- pipeline::PipelineError      (morphex/pipeline.h) with every problem and its location
//
// Errors are thrown before any work on the input that caused them. Two things are not errors of
// this kind: std::runtime_error is the environment failing (a disk, the index database), and
// other std::logic_errors are broken invariants (bugs). compute_boolean is the one operation that
// reports invalid operands in its result (BooleanResult::status), so that chains can branch on it
// without exceptions; the other operations throw InvalidSolid.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

namespace morphex {

class Error : public std::invalid_argument {
 public:
  Error(std::string where, std::string problem)
      : std::invalid_argument(where.empty() ? problem : where + ": " + problem),
        where_(std::move(where)),
        problem_(std::move(problem)) {}
  const std::string& where() const { return where_; }
  const std::string& problem() const { return problem_; }

 protected:
  // For errors whose message is composed otherwise (several problems).
  Error(std::string where, std::string problem, const std::string& what)
      : std::invalid_argument(what), where_(std::move(where)), problem_(std::move(problem)) {}

 private:
  std::string where_, problem_;
};

class InputError : public Error {
 public:
  using Error::Error;
};

class InvalidSolid : public InputError {
 public:
  using InputError::InputError;
};

}  // namespace morphex
