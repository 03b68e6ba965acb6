// SPDX-License-Identifier: GPL-3.0-or-later
// Each triangle's plane in doubles (check_planes.h).
#include "check/check_planes.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <stdexcept>
#include <thread>

namespace morphex::detail {

FacePlanes::FacePlanes(const Mesh& mesh, const std::vector<Xyz>& xyz, double error)
    : mesh_(mesh), xyz_(xyz), error_(error) {
  if (xyz.empty()) return;
  const std::size_t nf = mesh.num_triangles();
  // Every cursor holds at most one block partly filled: the blocks of all records, plus one each.
  num_cursors_ = std::size_t(std::max(1, tbb::this_task_arena::max_concurrency())) + 1;
  cursors_.reset(new Cursor[num_cursors_]);
  num_blocks_ = (nf + kBlock - 1) / kBlock + num_cursors_;
  blocks_.reset(new std::atomic<Plane*>[num_blocks_]);
  for (std::size_t i = 0; i < num_blocks_; ++i)
    blocks_[i].store(nullptr, std::memory_order_relaxed);
  slot_.reset(new std::atomic<std::uint32_t>[nf]);
  units_.resize(nf);
  proper_.resize(nf);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nf, 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t t = range.begin(); t != range.end(); ++t) {
                        slot_[t].store(kNone, std::memory_order_relaxed);
                        const Triangle& f = mesh.triangles[t];
                        const Xyz &p = xyz[f[0]], &q = xyz[f[1]], &r = xyz[f[2]];
                        const Xyz a = {q[0] - p[0], q[1] - p[1], q[2] - p[2]},
                                  b = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
                        const Xyz n = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                                       a[0] * b[1] - a[1] * b[0]};
                        const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
                        units_[t] = length > 0 && std::isfinite(length)
                                        ? Xyz{n[0] / length, n[1] / length, n[2] / length}
                                        : Xyz{0, 0, 0};
                        // Seen along some axis the corners turn: the face is not degenerate.
                        bool turns = false;
                        for (int k = 0; k < 3 && !turns; ++k) {
                          const int u = k == 0 ? 1 : 0, v = k == 2 ? 1 : 2;
                          const std::optional<int> o =
                              error == 0 ? static_orientation_2(u, v, p, q, r)
                                         : static_orientation_2_near(u, v, p, q, r, error);
                          turns = o && *o != 0;
                        }
                        proper_[t] = turns;
                      }
                    });
}

FacePlanes::~FacePlanes() {
  const std::size_t used = std::min<std::size_t>(blocks_used_.load(), num_blocks_);
  for (std::size_t b = 0; b < used; ++b) delete[] blocks_[b].load();
}

std::uint32_t FacePlanes::new_block(std::uint32_t face) const {
  const std::uint32_t b = blocks_used_.fetch_add(1, std::memory_order_relaxed);
  try {
    if (b >= num_blocks_) throw std::logic_error("FacePlanes: more blocks than cursors allow");
    blocks_[b].store(new Plane[kBlock], std::memory_order_release);
  } catch (...) {
    slot_[face].store(kNone, std::memory_order_release);  // no thread waits on it forever
    throw;
  }
  return b * kBlock;
}

// The threads that ask for this object's records are the check's own: its calling thread and
// those running its tasks, each in its own slot of the arena while the tasks exist (a thread
// runs one task at a time, and this runs no task). A thread outside any slot (-2) takes the
// shared cursor under the lock.
std::uint32_t FacePlanes::next_record(std::uint32_t face) const {
  const int thread = tbb::this_task_arena::current_thread_index();
  const bool own = thread >= 0 && std::size_t(thread) + 1 < num_cursors_;
  std::unique_lock<std::mutex> lock(shared_cursor_, std::defer_lock);
  if (!own) lock.lock();  // a thread outside the arena's slots: the last cursor, shared
  Cursor& c = cursors_[own ? std::size_t(thread) : num_cursors_ - 1];
  if (c.next == c.end) {
    c.next = new_block(face);
    c.end = c.next + kBlock;
  }
  return c.next++;
}

const FacePlanes::Plane& FacePlanes::publish(std::uint32_t t) const {
  // Claim the face, or wait while another thread writes its record (it gives the face back if
  // its allocation fails).
  for (std::uint32_t slot = kNone;
       !slot_[t].compare_exchange_weak(slot, kBusy, std::memory_order_acquire); slot = kNone) {
    if (slot >= kFirstRecord) return record(slot - kFirstRecord);
    std::this_thread::yield();
  }
  const std::uint32_t index = next_record(t);
  const Triangle& f = mesh_.triangles[t];
  const Xyz &p = xyz_[f[0]], &q = xyz_[f[1]], &r = xyz_[f[2]];
  Plane& plane =
      blocks_[index >> kBlockShift].load(std::memory_order_relaxed)[index & (kBlock - 1)];
  plane.plane = DoublePlane::through(p, q, r);
  plane.corner[0] = p, plane.corner[1] = q, plane.corner[2] = r;
  slot_[t].store(kFirstRecord + index, std::memory_order_release);
  return plane;
}

}  // namespace morphex::detail
