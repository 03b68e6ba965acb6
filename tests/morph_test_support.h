// SPDX-License-Identifier: GPL-3.0-or-later
// Exact checks shared by the morphology tests: a result's validity and volume, and inclusion of
// one solid in another by the volume of their difference.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "morphex/boolean.h"
#include "morphex/check.h"

namespace morphex::test_support {

// The exact volume of a mesh that must be a valid solid (a failure names `what`).
inline FT valid_volume(const Mesh& mesh, const std::string& what) {
  const MeshReport report = check_mesh(mesh);
  EXPECT_TRUE(report.valid_solid()) << what << ": " << describe_problems(report);
  return report.volume;
}

// vol(a minus b): zero exactly when a is inside b (up to a null set).
inline FT volume_outside(const Mesh& a, const Mesh& b) {
  const BooleanResult r = compute_boolean(check_solid(a), check_solid(b), BooleanOp::Difference);
  return valid_volume(r.solid, "difference");
}

}  // namespace morphex::test_support
