// SPDX-License-Identifier: GPL-3.0-or-later
// Each triangle's plane in doubles (check_planes.h).
#include "check_planes.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <thread>

namespace morphex::detail {

FacePlanes::FacePlanes(const Mesh& mesh, const std::vector<Xyz>& xyz, double error)
    : mesh_(mesh), xyz_(xyz), error_(error) {
  if (xyz.empty()) return;
  const std::size_t nf = mesh.num_triangles();
  const std::size_t num_blocks = (nf + kBlock - 1) / kBlock;
  blocks_.reset(new std::atomic<Plane*>[num_blocks]);
  for (std::size_t i = 0; i < num_blocks; ++i) blocks_[i].store(nullptr, std::memory_order_relaxed);
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
  if (!blocks_) return;
  const std::uint32_t used = used_.load();
  for (std::uint32_t b = 0; b * kBlock < used; ++b) delete[] blocks_[b].load();
}

const FacePlanes::Plane& FacePlanes::publish(std::uint32_t t) const {
  // Claim the face, or wait while another thread writes its record (it gives the face back if
  // its allocation fails).
  for (std::uint32_t slot = kNone;
       !slot_[t].compare_exchange_weak(slot, kBusy, std::memory_order_acquire); slot = kNone) {
    if (slot >= kFirstRecord) return record(slot - kFirstRecord);
    std::this_thread::yield();
  }
  const std::uint32_t index = used_.fetch_add(1, std::memory_order_relaxed);
  std::atomic<Plane*>& block = blocks_[index >> kBlockShift];
  if (!block.load(std::memory_order_acquire)) {
    const std::lock_guard<std::mutex> lock(new_block_);
    try {
      if (!block.load(std::memory_order_relaxed))
        block.store(new Plane[kBlock], std::memory_order_release);
    } catch (...) {
      slot_[t].store(kNone, std::memory_order_release);  // no thread waits on it forever
      throw;
    }
  }
  const Triangle& f = mesh_.triangles[t];
  const Xyz &p = xyz_[f[0]], &q = xyz_[f[1]], &r = xyz_[f[2]];
  const double a[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
  const double b[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
  Plane& plane = block.load(std::memory_order_relaxed)[index & (kBlock - 1)];
  plane.reach = 0;
  plane.corner[0] = p, plane.corner[1] = q, plane.corner[2] = r;
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    plane.normal[k] = a[i] * b[j] - a[j] * b[i];
    plane.magnitude[k] = std::fabs(a[i] * b[j]) + std::fabs(a[j] * b[i]);
    plane.reach = std::max({plane.reach, std::fabs(a[k]), std::fabs(b[k])});
  }
  slot_[t].store(kFirstRecord + index, std::memory_order_release);
  return plane;
}

}  // namespace morphex::detail
