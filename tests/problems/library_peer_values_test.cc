// A peer's published optimum of a discrete NLP (ProblemInfo::additional_references with a scheme
// and a grid: CTBenchmarks' trapezoid objectives, ...) is a check that OCPBench's transcription
// of that scheme and grid IS the peer's NLP: Ipopt's objective must reproduce it to 1e-8
// relative. Grids above kMaxTestedIntervals are left to the library suite (Release; its
// summary's column "NLP vs peer"), to bound the sanitizer build's test time.
#include <cstdio>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "core/parameters.h"
#include "problems/registry.h"
#include "tests/problems/reference_test_support.h"

namespace ocpb {
namespace {

using reference_testing::RelativeError;
using reference_testing::Request;
using reference_testing::SolveWith;

constexpr int kMaxTestedIntervals = 500;
constexpr double kPeerTolerance = 1e-8;

TEST(LibraryPeerValues, TranscriptionsReproduceThePeersNlpOptima) {
  int checked = 0;
  for (const ProblemInfo& info : Problems()) {
    for (const ProblemReference& peer : info.additional_references) {
      if (peer.scheme == "continuous" || peer.quantity != "J") continue;
      if (peer.intervals > kMaxTestedIntervals) continue;
      const std::unique_ptr<Ocp> ocp = info.make(Parameters(info.parameters), 1);
      const SolveResult result = SolveWith(
          "ipopt",
          *ocp,
          Request(*ocp, peer.intervals, TerminalMode::kHard, peer.scheme, {{"tol", "1e-10"}}));
      const std::string what = info.name + ", " + peer.scheme +
                               " N = " + std::to_string(peer.intervals) + " (" + peer.source + ")";
      EXPECT_EQ(result.status, SolveStatus::kConverged) << what << ": " << result.message;
      EXPECT_LE(RelativeError(result.objective, peer.value), kPeerTolerance)
          << what << ": objective " << result.objective << " against " << peer.value;
      ++checked;
    }
  }
  RecordProperty("peer_values_checked", checked);
  std::printf("peer values checked at the NLP level: %d\n", checked);
}

}  // namespace
}  // namespace ocpb
