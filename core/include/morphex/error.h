// SPDX-License-Identifier: GPL-3.0-or-later
// The error model of every morphex library (core, libbool, libmorph, pipelines, libretrieval) and
// of the Python module: one hierarchy, thrown, never returned as a status.
//
//   morphex::Error                    what() is "<where>: <problem>": where names the file,
//   |                                 operand, option or JSON path ("" when the caller knows it
//   |                                 better), problem says what is wrong and where inside it
//   |                                 (line, vertex, face).
//   +- InputError                     an input that cannot be used: a file, a mesh, a number, an
//   |  |                              option. Thrown before any work on it. CLI exit code 2;
//   |  |                              Python morphex.InputError (a ValueError).
//   |  +- InvalidSolid                a mesh that is not a valid solid where one is needed
//   |  +- StructuringElementError     (morphex/structuring_element.h) the parameter at fault
//   |  +- pipeline::PipelineError     (morphex/pipeline.h) every problem with its location
//   +- OutputError                    a result that cannot be stored as asked. Exit code 1;
//   |  |                              Python morphex.OutputError.
//   |  +- LossyOutputError            the chosen plain format cannot hold the result at all (a
//   |                                 coordinate beyond a float's range)
//   +- StorageError                   the environment fails: a file that cannot be opened or
//                                     written, a full disk, an index database that cannot be
//                                     used. Exit code 1; Python morphex.StorageError (an OSError).
//
// Two things are not morphex errors: std::logic_error is a broken invariant (a bug, please report
// it), std::bad_alloc and std::system_error are the machine running out of memory or threads.
// Validity is a type, not a status: the operations that need a valid solid take a Solid
// (morphex/solid.h), so they have no invalid operand to report.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

namespace morphex {

class Error : public std::runtime_error {
 public:
  Error(std::string where, std::string problem)
      : std::runtime_error(where.empty() ? problem : where + ": " + problem),
        where_(std::move(where)),
        problem_(std::move(problem)) {}
  const std::string& where() const { return where_; }
  const std::string& problem() const { return problem_; }

 protected:
  // For errors whose message is composed otherwise (several problems).
  Error(std::string where, std::string problem, const std::string& what)
      : std::runtime_error(what), where_(std::move(where)), problem_(std::move(problem)) {}

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

class OutputError : public Error {
 public:
  using Error::Error;
};

class LossyOutputError : public OutputError {
 public:
  using OutputError::OutputError;
};

class StorageError : public Error {
 public:
  using Error::Error;
};

}  // namespace morphex
