// The classic group of the reference library (problems/library/classic/): every problem is
// registered with a reference and tags, and the closed forms the references rest on hold.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "problems/library/classic/hypersensitive.h"
#include "problems/library/classic/neuenhofen_kerrigan_x1.h"
#include "problems/registry.h"

namespace ocpb {
namespace {

const std::vector<std::string>& ClassicNames() {
  static const std::vector<std::string> names = {
      "hypersensitive",
      "alp-rider",
      "singular-double-integrator",
      "lotka-volterra-fishing",
      "tumor-antiangiogenesis",
      "vanderpol-state-constrained",
      "f8-aircraft",
      "neuenhofen-kerrigan-x1",
      "min-energy-free-velocity",
      "min-energy-target-line",
  };
  return names;
}

TEST(LibraryClassic, EveryProblemIsRegisteredWithAReferenceAndTags) {
  for (const std::string& name : ClassicNames()) {
    SCOPED_TRACE(name);
    const ProblemInfo& info = FindProblem(name);
    ASSERT_TRUE(info.reference_value.has_value());
    EXPECT_TRUE(std::isfinite(*info.reference_value));
    EXPECT_FALSE(info.reference_source.empty());
    EXPECT_FALSE(info.tags.empty());
    const auto ocp = MakeProblem(name, {}, 0);
    EXPECT_EQ(ocp->name(), name);
  }
}

// J_inf = V(1) + W(1.5) from the Hamilton-Jacobi closed form, against Betts' 6.7241.
TEST(LibraryClassic, HypersensitiveLongHorizonCost) {
  EXPECT_NEAR(Hypersensitive::InfiniteHorizonCost(), 6.72411380988600, 1e-13);
  EXPECT_NEAR(Hypersensitive::InfiniteHorizonCost(), 6.7241, 5e-5);
}

// The closed form of X1 satisfies y' = y^2/2 + u, y(0) = 0, and its cost is J*.
TEST(LibraryClassic, NeuenhofenKerriganClosedForm) {
  const double h = 1e-6;
  for (double t : {0.1, 0.7, 1.3}) {
    const double dy =
        (NeuenhofenKerriganX1::OptimalState(t + h) - NeuenhofenKerriganX1::OptimalState(t - h)) /
        (2.0 * h);
    const double y = NeuenhofenKerriganX1::OptimalState(t);
    EXPECT_NEAR(dy, 0.5 * y * y + NeuenhofenKerriganX1::OptimalControl(t), 1e-8);
  }
  EXPECT_EQ(NeuenhofenKerriganX1::OptimalState(0.0), 0.0);
  const int n = 200000;
  const double step = std::acos(-1.0) / 2.0 / n;
  double cost = 0.0;
  for (int i = 0; i < n; ++i) {
    const double t = (i + 0.5) * step;
    const double y = NeuenhofenKerriganX1::OptimalState(t);
    cost += step * (y * y + std::cos(t) * NeuenhofenKerriganX1::OptimalControl(t));
  }
  EXPECT_NEAR(cost, NeuenhofenKerriganX1::kReferenceCost, 1e-9);
}

}  // namespace
}  // namespace ocpb
