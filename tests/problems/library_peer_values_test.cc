// A peer's published optimum of a discrete NLP (a problem's discrete reference: the primary one
// or ProblemInfo::additional_references with a scheme and a grid; CTBenchmarks' trapezoid
// objectives, ...) is a check that OCPBench's transcription of that scheme and grid IS the
// peer's NLP: Ipopt's objective must reproduce it to 1e-8 relative. Grids above
// kMaxTestedIntervals are left to the library suites (Release; their summaries' column "NLP vs
// peer"), to bound the sanitizer build's test time.
#include <cstdio>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/parameters.h"
#include "problems/registry.h"
#include "tests/problems/reference_test_support.h"
#include "transcriptions/registry.h"

namespace ocpb {
namespace {

using reference_testing::RelativeError;
using reference_testing::Request;
using reference_testing::SolveWith;

constexpr int kMaxTestedIntervals = 200;
constexpr double kPeerTolerance = 1e-8;

// COPS prints its optima to 6 digits: goddard's and robot-arm's primary references are checked
// to that precision by their own tests (reference_*_test.cc), not to 1e-8 here.
const std::set<std::string>& PrintedToSixDigits() {
  static const std::set<std::string> names = {"goddard", "robot-arm"};
  return names;
}

TEST(LibraryPeerValues, TranscriptionsReproduceThePeersNlpOptima) {
  int checked = 0;
  for (const ProblemInfo& info : Problems()) {
    // Each discrete reference with the Ipopt options it needs (the primary one may name some).
    std::vector<std::pair<ProblemReference, std::vector<std::pair<std::string, std::string>>>>
        discrete;
    for (const ProblemReference& r : info.additional_references) {
      discrete.push_back({r, r.options});
    }
    if (info.reference_value && info.reference_scheme != "continuous" &&
        !PrintedToSixDigits().count(info.name)) {
      discrete.push_back({{*info.reference_value,
                           info.reference_quantity,
                           info.reference_scheme,
                           info.reference_intervals,
                           info.reference_source},
                          info.reference_options});
    }
    for (const auto& [peer, peer_options] : discrete) {
      if (peer.scheme == "continuous" || peer.quantity != "J") continue;
      if (peer.intervals > kMaxTestedIntervals) continue;
      // A scheme OCPBench does not have (COPS' Gauss-Legendre for catmix) is not checked.
      bool known = false;
      for (const TranscriptionInfo& t : Transcriptions()) known = known || t.name == peer.scheme;
      if (!known) continue;
      const std::unique_ptr<Ocp> ocp = info.make(Parameters(info.parameters), 1);
      // A tolerance tighter than the peers', and the options a reference says it needs.
      std::map<std::string, std::string> options = {{"tol", "1e-10"}};
      for (const auto& [key, value] : peer_options) options[key] = value;
      const SolveResult result = SolveWith(
          "ipopt", *ocp, Request(*ocp, peer.intervals, TerminalMode::kHard, peer.scheme, options));
      const std::string what = info.name + ", " + peer.scheme +
                               " N = " + std::to_string(peer.intervals) + " (" + peer.source + ")";
      EXPECT_EQ(result.status, SolveStatus::kConverged) << what << ": " << result.message;
      EXPECT_LE(RelativeError(result.objective, peer.value), kPeerTolerance)
          << what << ": objective " << result.objective << " against " << peer.value;
      ++checked;
    }
  }
  std::printf("peer values checked at the NLP level: %d\n", checked);
  EXPECT_GE(checked, 10);  // the library's peers at N <= 200 (a lost reference fails here)
}

}  // namespace
}  // namespace ocpb
