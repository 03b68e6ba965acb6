// SPDX-License-Identifier: GPL-3.0-or-later
// The MPI calls `morphex index` makes across ranks, as a module (morphex_mpi.so, built from
// mpi_transport.cpp) that only an MPI run loads: linked, Open MPI and the libraries it brings took
// about 4 ms of every command's start. Plain C types only cross between the module and
// index_mpi.cpp; every call is on MPI_COMM_WORLD.
#pragma once

#include <cstddef>

namespace morphex::detail {

struct MpiTransport {
  // MPI_Init_thread (funneled) and this rank's place; false when MPI could not start.
  bool (*init)(int* rank, int* size, int* ranks_on_node);
  void (*finalize)();
  void (*send)(const char* data, int size, int to, int tag);
  // A message from `from` (-1: any rank) with `tag` (-1: any tag): waits for one when `wait`,
  // else only looks. True when one is there: its source, tag and size in bytes.
  bool (*probe)(int from, int tag, bool wait, int* source, int* found_tag, int* size);
  void (*receive)(char* data, int size, int source, int tag);
  // Waits for every rank without spinning a core (a finished rank must not slow the ones still
  // working on the same node, as a blocking barrier's busy wait would).
  void (*quiet_barrier)();
};

inline constexpr const char* kMpiModule = "morphex_mpi.so";
inline constexpr const char* kMpiTransport = "morphex_mpi_transport";  // const MpiTransport* ()
using GetMpiTransport = const MpiTransport* (*)();

}  // namespace morphex::detail
