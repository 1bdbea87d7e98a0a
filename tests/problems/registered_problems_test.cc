// Every problem in the registry, found by iterating it (a new problem is checked by being
// registered, not by being added to a list): its first and second derivatives against finite
// differences, and the consistency of its registry entry.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/derivative_check.h"
#include "core/parameters.h"
#include "problems/registry.h"
#include "transcriptions/registry.h"

namespace ocpb {
namespace {

// How a problem is checked: near x0 within spread * max(1, |x0_i|), to a relative error below
// tolerance, with parameter settings under which the check is meaningful and cheap. Every
// problem without an entry is checked with the defaults.
struct CheckSetting {
  std::vector<std::string> set;
  double spread = 0.3;
  double tolerance = 1e-7;
};

const std::map<std::string, CheckSetting>& CheckSettings() {
  static const std::map<std::string, CheckSetting> settings = {
      // With eps > 0 its running cost has a Hessian to check.
      {"catmix", {{"eps=0.3"}}},
      // The analytic path-loss channel: the map's and the GP's derivatives have their own tests
      // (tests/problems/comm_path2d_test.cc, tests/channel/).
      {"comm-path2d", {{"channel=0"}}},
      {"comm-fixed-path", {{"channel=0"}}},
      // Goddard's drag varies like exp(-500 (h - 1)): near its own scale, and central
      // differences (step 6e-6) then have a relative truncation error of (500 * 6e-6)^2 / 6 =
      // 1.5e-6 in the Hessian (tests/problems/reference_free_time_test.cc measured 1.5e-6).
      {"goddard", {{}, 0.01, 1e-5}},
      // The same for the launch vehicle's air, exp(-885 (|r| - 1)) with r in Earth radii: near
      // the ground, where a spread of 0.3 puts the rocket 2000 km under it (density e^265).
      {"launch-vehicle", {{}, 0.01, 1e-5}},
      // Its rates divide by (theta2 + theta5) y1 + y2, which the default spread could bring near
      // 0 in a later phase (y1 ~ 1e-3 there): near the observations, where it is above 0.1.
      {"methanol", {{}, 0.05, 1e-7}},
      // Phase durations up to 13800 (s) scale its stacked dynamics: central differences of f
      // measured 1.3e-7 relative (the rates are exact, by AD).
      {"pinene", {{}, 0.3, 1e-6}},
  };
  return settings;
}

// A point near the problem's start: x = x0 + spread max(1, |x0|) unit, u inside U's bounding
// box (0.5 +- 0.4 where unbounded) projected onto U, multipliers of order one.
void DrawRandomPoint(const Ocp& ocp,
                     double spread,
                     std::mt19937_64* rng,
                     double* t,
                     Vec* x,
                     Vec* u,
                     Vec* lambda,
                     Vec* mu,
                     Vec* nu) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  *t = ocp.t0() + 0.5 * (1.0 + unit(*rng)) * (ocp.tf() - ocp.t0());
  *x = Vec(ocp.nx());
  for (int i = 0; i < ocp.nx(); ++i) {
    (*x)[i] = ocp.x0()[i] + spread * std::max(1.0, std::abs(ocp.x0()[i])) * unit(*rng);
  }
  Vec lo, hi;
  ocp.control_set().BoundingBox(&lo, &hi);
  *u = Vec(ocp.nu());
  for (int i = 0; i < ocp.nu(); ++i) {
    const double a = std::isfinite(lo[i]) ? lo[i] : 0.1, b = std::isfinite(hi[i]) ? hi[i] : 0.9;
    (*u)[i] = a + (b - a) * (0.5 + 0.4 * unit(*rng));
  }
  ocp.control_set().Project(*u);
  *lambda = Vec(ocp.nx());
  for (int i = 0; i < ocp.nx(); ++i) (*lambda)[i] = 2.0 * unit(*rng);
  *mu = Vec(ocp.num_path());
  for (int i = 0; i < ocp.num_path(); ++i) (*mu)[i] = 1.0 + unit(*rng);
  *nu = Vec(ocp.num_terminal());
  for (int i = 0; i < ocp.num_terminal(); ++i) (*nu)[i] = 2.0 * unit(*rng);
}

// A seed from the problem's name (FNV-1a), so that a problem's points do not depend on where
// it sits in the registry: registering a new problem does not move the others' draws.
std::uint64_t SeedOf(const std::string& name) {
  std::uint64_t h = 1469598103934665603ull;
  for (const char c : name) h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  return h;
}

TEST(RegisteredProblems, DerivativesMatchFiniteDifferences) {
  size_t checked = 0;
  for (const ProblemInfo& info : Problems()) {
    std::mt19937_64 rng(SeedOf(info.name));
    const auto it = CheckSettings().find(info.name);
    const CheckSetting setting = it == CheckSettings().end() ? CheckSetting() : it->second;
    const auto ocp = MakeProblem(info.name, setting.set, 1);
    for (int trial = 0; trial < 5; ++trial) {
      double t = 0.0;
      Vec x, u, lambda, mu, nu;
      DrawRandomPoint(*ocp, setting.spread, &rng, &t, &x, &u, &lambda, &mu, &nu);
      const DerivativeCheck check = CheckOcpDerivatives(*ocp, t, x, u, lambda, mu, nu);
      EXPECT_LT(check.max_error, setting.tolerance) << info.name << " at trial " << trial << "\n"
                                                    << check.log;
    }
    ++checked;
  }
  EXPECT_EQ(checked, Problems().size());
  EXPECT_GE(checked, 17u);  // the built-in problems, at least
}

// What `ocpbench describe`, suites and records read from an entry holds together for every
// registered problem: defaults satisfy their own ranges, the default grid is positive, a
// discrete reference names its grid.
TEST(RegisteredProblems, EntriesAreConsistent) {
  for (const ProblemInfo& info : Problems()) {
    EXPECT_FALSE(info.description.empty()) << info.name;
    EXPECT_GT(info.default_intervals, 0) << info.name;
    OptionSchema schema(info.name);
    for (const ParameterSpec& p : info.parameters) {
      EXPECT_NO_THROW(schema.Add(ToOptionSpec(p))) << info.name << "." << p.name;
    }
    if (info.reference_value) {
      EXPECT_TRUE(std::isfinite(*info.reference_value)) << info.name;
      EXPECT_FALSE(info.reference_source.empty()) << info.name;
      if (info.reference_scheme != "continuous") {
        EXPECT_GT(info.reference_intervals, 0) << info.name;
      }
    }
    // Tags: at least one, each from the vocabulary (`ocpbench list problems --tag T`).
    EXPECT_FALSE(info.tags.empty()) << info.name << " has no tag";
    for (const std::string& tag : info.tags) {
      EXPECT_NO_THROW(CheckProblemTag(info.name, tag)) << info.name << ": " << tag;
    }
    // Further references: a value, a source, and a grid exactly when discrete, in a scheme
    // OCPBench has (the library suite and the NLP-level test solve that NLP).
    for (const ProblemReference& r : info.additional_references) {
      EXPECT_TRUE(std::isfinite(r.value)) << info.name;
      EXPECT_FALSE(r.source.empty()) << info.name;
      if (r.scheme == "continuous") {
        EXPECT_EQ(r.intervals, 0) << info.name;
      } else {
        EXPECT_GT(r.intervals, 0) << info.name;
        EXPECT_NO_THROW(FindTranscription(r.scheme)) << info.name << ": " << r.scheme;
      }
    }
  }
}

// Every registered problem but the paper's (whose measure is the paper's reproduction:
// problems/README-paper.md) carries at least one published reference value.
TEST(RegisteredProblems, EveryProblemHasAReference) {
  for (const ProblemInfo& info : Problems()) {
    if (std::find(info.tags.begin(), info.tags.end(), "paper") != info.tags.end()) continue;
    EXPECT_TRUE(info.reference_value.has_value() || !info.additional_references.empty())
        << info.name << " has no reference value";
  }
}

}  // namespace
}  // namespace ocpb
