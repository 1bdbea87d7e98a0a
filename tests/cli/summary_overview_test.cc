// The overview of a suite of many problems (bench/cli/summary_overview.h) on synthetic records:
// which case stands for a family on a problem, what counts as solved, and the profile's rho.
#include "bench/cli/summary_overview.h"

#include "bench/cli/summary.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace ocpb {
namespace {

Record Case(const std::string& problem,
            const std::string& solver,
            const std::string& transcription,
            const std::string& status,
            double Jbar_fine,
            double cpu,
            double reference = 1.0) {
  Record r;
  r.problem = problem;
  r.solver = solver;
  r.transcription = transcription;
  r.terminal = "hard";
  r.status = status;
  r.J_fine = r.Jbar_fine = Jbar_fine;
  r.cpu_seconds = cpu;
  r.reference = RecordReference{reference, "J", "test", "continuous", 0};
  return r;
}

TEST(SummaryOverview, FamilyNamesSolverTranscriptionAlgorithmAndScheme) {
  Record r = Case("a", "ipopt", "lgr", "converged", 1.0, 1.0);
  EXPECT_EQ(MethodFamily(r), "ipopt + lgr");
  r.algorithm = "LD_SLSQP";
  r.transcription = "hermite-simpson";
  r.solver = "nlopt";
  EXPECT_EQ(MethodFamily(r), "nlopt + hermite-simpson (LD_SLSQP)");
  // The Hamiltonian family's scheme option: rk4 is another family, euler (its default) is not.
  Record h = Case("a", "hamiltonian-al", "", "converged", 1.0, 1.0);
  EXPECT_EQ(MethodFamily(h), "hamiltonian-al");
  h.options["scheme"] = "euler";
  EXPECT_EQ(MethodFamily(h), "hamiltonian-al");
  h.options["scheme"] = "rk4";
  EXPECT_EQ(MethodFamily(h), "hamiltonian-al (rk4)");
}

TEST(SummaryOverview, BestCaseSolvedStatusAndProfile) {
  const std::vector<Record> records = {
      // a: hermite-simpson converged to 1e-9 at 2 s, and a faster non-converged case that
      // must not stand for the family; euler converged, 1e-4 off (not solved).
      Case("a", "ipopt", "hermite-simpson", "max_iterations", 1.0, 0.5),
      Case("a", "ipopt", "hermite-simpson", "converged", 1.0 + 1e-9, 2.0),
      Case("a", "ipopt", "euler", "converged", 1.0 + 1e-4, 1.0),
      // b: both solve, euler four times faster.
      Case("b", "ipopt", "hermite-simpson", "converged", 1.0, 4.0),
      Case("b", "ipopt", "euler", "converged", 1.0, 1.0),
      // c: euler is not applicable, hermite-simpson solves.
      Case("c", "ipopt", "hermite-simpson", "converged", 1.0, 1.0),
      Case("c", "ipopt", "euler", "not_applicable", NAN, 0.0),
  };
  const Overview o = BuildOverview(records);
  ASSERT_EQ(o.problems, (std::vector<std::string>{"a", "b", "c"}));
  ASSERT_EQ(o.families, (std::vector<std::string>{"ipopt + hermite-simpson", "ipopt + euler"}));
  EXPECT_EQ(o.cell[0][0].cases, 2);
  EXPECT_EQ(o.cell[0][0].status, "converged");
  EXPECT_DOUBLE_EQ(o.cell[0][0].cpu_seconds, 2.0);
  EXPECT_TRUE(o.cell[0][0].solved);
  EXPECT_FALSE(o.cell[0][1].solved);  // 1e-4 from the reference
  EXPECT_TRUE(o.cell[1][1].solved);
  EXPECT_EQ(o.cell[2][1].status, "not_applicable");

  const std::string md = OverviewMarkdown(records);
  // hermite-simpson: applies to 3, solves 3, fastest on a and c; within 4x on b.
  EXPECT_NE(md.find("| ipopt + hermite-simpson | 3 | 3 | 2 | 0.67 | 0.67 | 1.00 | 1.00 |"),
            std::string::npos)
      << md;
  // euler: applies to a and b only, solves b, where it is the fastest.
  EXPECT_NE(md.find("| ipopt + euler | 2 | 1 | 1 | 0.50 | 0.50 | 0.50 | 0.50 |"), std::string::npos)
      << md;
  EXPECT_NE(md.find("| c | **0** (1 s) | n/a |"), std::string::npos) << md;
  // A suite of fewer problems than asked for gets no overview.
  EXPECT_EQ(OverviewMarkdown(records, 4), "");
}

// A record's nlp_reference (a peer's optimum of the very NLP it solved) survives the record's
// JSON, and the summary compares the record's own objective with it in "NLP vs peer".
TEST(SummaryOverview, NlpReferenceRoundTripsAndIsCompared) {
  Record r = Case("p", "ipopt", "trapezoid", "converged", 1.0, 0.1);
  r.N = 200;
  r.objective = 2.0 * (1.0 + 3e-9);
  r.nlp_reference = RecordReference{2.0, "J", "peer, trapezoid N = 200", "trapezoid", 200};
  const Record back = Record::FromJson(r.ToJson());
  ASSERT_TRUE(back.nlp_reference.has_value());
  EXPECT_EQ(back.nlp_reference->value, 2.0);
  EXPECT_EQ(back.nlp_reference->scheme, "trapezoid");
  EXPECT_EQ(back.nlp_reference->N, 200);
  EXPECT_EQ(back.nlp_reference->source, "peer, trapezoid N = 200");
  const std::string md = SummaryMarkdown("s", {back});
  EXPECT_NE(md.find(" NLP vs peer |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 3e-09 |"), std::string::npos) << md;
}

// The families by tag count, per tag, the problems with a continuous reference that each
// family solved among those it applies to; a problem without a continuous reference, or whose
// tags are unknown, is left out.
TEST(SummaryOverview, TagTableCountsSolvedOverApplicableProblemsWithAContinuousReference) {
  std::vector<Record> records = {
      Case("a", "ipopt", "hermite-simpson", "converged", 1.0, 1.0),       // solved
      Case("a", "ipopt", "euler", "converged", 1.0 + 1e-3, 1.0),          // not solved
      Case("b", "ipopt", "hermite-simpson", "converged", 1.0, 1.0),       // solved
      Case("b", "ipopt", "euler", "not_applicable", NAN, 0.0),            // does not apply
      Case("c", "ipopt", "hermite-simpson", "max_iterations", 1.0, 1.0),  // not converged
      Case("c", "ipopt", "euler", "converged", 1.0, 1.0),                 // solved
      Case("d", "ipopt", "hermite-simpson", "converged", 5.0, 1.0),       // no continuous ref.
  };
  records.back().reference.reset();
  const auto tags_of = [](const std::string& problem) -> std::vector<std::string> {
    if (problem == "a") return {"smooth", "free-time"};
    if (problem == "b" || problem == "d") return {"smooth"};
    if (problem == "c") return {"bang-bang"};
    return {};
  };
  const std::string md = TagTableMarkdown(BuildOverview(records), tags_of);
  EXPECT_NE(md.find("| tag (problems) | ipopt + hermite-simpson | ipopt + euler |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| smooth (2) | 2 / 2 | 0 / 1 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| free-time (1) | 1 / 1 | 0 / 1 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| bang-bang (1) | 0 / 1 | 1 / 1 |"), std::string::npos) << md;
  // One row per tag, in ProblemTags() order.
  EXPECT_EQ(md.find("| smooth ("), md.rfind("| smooth ("));
  EXPECT_LT(md.find("| smooth ("), md.find("| bang-bang ("));
  EXPECT_LT(md.find("| bang-bang ("), md.find("| free-time ("));
  // Nothing to count without tags.
  EXPECT_EQ(TagTableMarkdown(BuildOverview(records),
                             [](const std::string&) { return std::vector<std::string>{}; }),
            "");
}

}  // namespace
}  // namespace ocpb
