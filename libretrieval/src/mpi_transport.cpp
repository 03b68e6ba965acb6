// SPDX-License-Identifier: GPL-3.0-or-later
// The module morphex_mpi.so: mpi_transport.h's calls over MPI. The only file that includes mpi.h.
#include <mpi.h>

#include <chrono>
#include <thread>

#include "mpi_transport.h"

namespace {

bool init(int* rank, int* size, int* ranks_on_node) {
  int provided = 0;
  if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
    return false;
  MPI_Comm_rank(MPI_COMM_WORLD, rank);
  MPI_Comm_size(MPI_COMM_WORLD, size);
  MPI_Comm node;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, *rank, MPI_INFO_NULL, &node);
  MPI_Comm_size(node, ranks_on_node);
  MPI_Comm_free(&node);
  return true;
}

void finalize() {
  MPI_Finalize();
}

void send(const char* data, int size, int to, int tag) {
  MPI_Send(data, size, MPI_CHAR, to, tag, MPI_COMM_WORLD);
}

bool probe(int from, int tag, bool wait, int* source, int* found_tag, int* size) {
  MPI_Status status;
  const int any_from = from < 0 ? MPI_ANY_SOURCE : from, any_tag = tag < 0 ? MPI_ANY_TAG : tag;
  int arrived = 1;
  if (wait)
    MPI_Probe(any_from, any_tag, MPI_COMM_WORLD, &status);
  else if (MPI_Iprobe(any_from, any_tag, MPI_COMM_WORLD, &arrived, &status) != MPI_SUCCESS)
    arrived = 0;
  if (!arrived) return false;
  *source = status.MPI_SOURCE;
  *found_tag = status.MPI_TAG;
  MPI_Get_count(&status, MPI_CHAR, size);
  return true;
}

void receive(char* data, int size, int source, int tag) {
  MPI_Recv(data, size, MPI_CHAR, source, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
}

void quiet_barrier() {
  MPI_Request request;
  MPI_Ibarrier(MPI_COMM_WORLD, &request);
  int done = 0;
  while (MPI_Test(&request, &done, MPI_STATUS_IGNORE) == MPI_SUCCESS && !done)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
}

const morphex::detail::MpiTransport kTransport{init, finalize, send, probe, receive, quiet_barrier};

}  // namespace

extern "C" const morphex::detail::MpiTransport* morphex_mpi_transport() {
  return &kTransport;
}
