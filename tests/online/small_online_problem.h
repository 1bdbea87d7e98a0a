// The small comm-path2d problem the online tests share (fast under ASan): S = (20, 20),
// D = (10, 5), c = 75 bits, tf = 20 s in a 25 m workspace.
#pragma once

#include <Eigen/Core>

#include "problems/comm_path2d.h"

namespace ocpb::testing {

inline CommPath2d::Options SmallOnlineProblem() {
  CommPath2d::Options o;
  o.start = Eigen::Vector2d(20.0, 20.0);
  o.destination = Eigen::Vector2d(10.0, 5.0);
  o.bits = 75.0;
  o.tf = 20.0;
  o.workspace = 25.0;
  return o;
}

}  // namespace ocpb::testing
