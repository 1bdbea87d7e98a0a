// Reproduces the numbers of Ali, Cai, Mostofi and Wardi (ACC 2016), Section III, over several
// channel realizations, and writes the records the paper's figures are drawn from.
//
//   comm_paper_reproduction [--out DIR] [--seeds 1-10] [--channel 2]
//
// For every seed: comm-path2d with the paper's parameters (channel = 2: the paper's channel
// predicted from 500 samples, bicubic map), solved by the Hamiltonian descent
//   A. C = (10, 50, 10) with the paper's stopping rule (500 iterations, or Armijo exponent > 50);
//   A56. the same, stopped at 56 iterations (the paper's count);
//   B. C = (500, 500, 500), 500 iterations.
// Every result is judged by the common evaluator (Euler on the solver's grid, as everywhere in
// OCPBench). Writes DIR/seed<k>_<run>.json (the fields of `ocpbench solve --json` that the
// figures use; the 56-iteration record also carries the s map) and DIR/table.md (mean, standard
// deviation, min and max over the seeds next to the paper's values). Not a test: built on
// request (EXCLUDE_FROM_ALL).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/evaluator.h"
#include "problems/comm_path2d.h"
#include "problems/registry.h"
#include "solvers/hamiltonian_descent.h"

namespace ocpb {
namespace {

using nlohmann::json;

// Concatenation through a stream (GCC 12 warns falsely, -Werror=restrict, on "a" + std::string).
template <class... A>
std::string Cat(const A&... a) {
  std::ostringstream os;
  (os << ... << a);
  return os.str();
}

json Num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// 7 significant digits: plenty for figures, half the file size.
json Short(double v) {
  if (!std::isfinite(v)) return json(nullptr);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.7g", v);
  return json(std::stod(buf));
}

json Rows(const Mat& m) {
  json rows = json::array();
  for (int i = 0; i < m.rows(); ++i) {
    json row = json::array();
    for (int j = 0; j < m.cols(); ++j) row.push_back(Short(m(i, j)));
    rows.push_back(row);
  }
  return rows;
}

struct RunSummary {
  double J0 = NAN, J20 = NAN, J = NAN, Jbar = NAN, violation = NAN, cpu = NAN, final_theta = NAN;
  int iterations = 0;
  Vec x_final;
  std::string status;
};

// log10 s on a 0.5 m grid over the workspace (for the path figure).
json SMap(const CommPath2d& ocp) {
  json xs = json::array(), ys = json::array(), rows = json::array();
  const int n = 101;
  for (int i = 0; i < n; ++i) xs.push_back(50.0 * i / (n - 1));
  for (int j = 0; j < n; ++j) {
    ys.push_back(50.0 * j / (n - 1));
    json row = json::array();
    for (int i = 0; i < n; ++i) {
      double s = 0.0;
      ocp.channel().Evaluate(
          Eigen::Vector2d(50.0 * i / (n - 1), 50.0 * j / (n - 1)), &s, nullptr, nullptr);
      row.push_back(Short(std::log10(s)));
    }
    rows.push_back(row);
  }
  return json{{"x", xs}, {"y", ys}, {"log10_s", rows}, {"rows", "y"}};
}

RunSummary Run(const std::string& name,
               const std::vector<std::string>& set,
               std::uint64_t seed,
               const std::map<std::string, std::string>& options,
               const std::string& out_dir,
               bool with_map) {
  Parameters params;
  const std::unique_ptr<Ocp> ocp = MakeProblem("comm-path2d", set, seed, &params);
  const auto& cp = static_cast<const CommPath2d&>(*ocp);
  const int N = FindProblem("comm-path2d").default_intervals;
  SolveRequest request;
  request.grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), N);
  request.options = options;
  const SolveResult r = HamiltonianDescent().Solve(*ocp, request);
  const Evaluation ev = Evaluate(*ocp, r.controls, request.grid, Integrator::kEuler);

  RunSummary s;
  s.J0 = r.history.front().J;
  s.J20 = r.history.size() > 20 ? r.history[20].J : NAN;
  s.J = ev.J;
  s.Jbar = ev.Jbar;
  s.violation = ev.terminal_violation;
  s.cpu = r.cpu_seconds;
  s.iterations = r.iterations;
  s.x_final = ev.X.col(N);
  s.status = r.solver_status;
  s.final_theta = r.history.back().theta;

  json rec;
  rec["problem"] = "comm-path2d";
  json pj = json::object();
  for (const auto& [k, v] : params.values()) pj[k] = v.size() == 1 ? json(v[0]) : json(v);
  rec["parameters"] = pj;
  rec["seed"] = seed;
  rec["channel"] = cp.channel().Describe();
  rec["solver"] = "hamiltonian";
  rec["options"] = options;
  rec["N"] = N;
  rec["status"] = ToString(r.status);
  rec["solver_status"] = r.solver_status;
  rec["message"] = r.message;
  rec["objective"] = Num(r.objective);
  rec["iterations"] = r.iterations;
  rec["cpu_seconds"] = Num(r.cpu_seconds);
  rec["J"] = Num(ev.J);
  rec["Jbar"] = Num(ev.Jbar);
  rec["terminal_violation"] = Num(ev.terminal_violation);
  rec["final_state"] = Rows(ev.X.col(N).transpose())[0];
  rec["trajectory"] = json{{"t", request.grid.points()},
                           {"x", Rows(ev.X)},
                           {"u", Rows(r.controls.values())},
                           {"u_rule", "piecewise constant, value on [t_k, t_k+1)"}};
  json hist = json::array();
  for (const IterationRecord& h : r.history) {
    hist.push_back(json{{"iteration", h.iteration},
                        {"J", Num(h.J)},
                        {"theta", Num(h.theta)},
                        {"armijo_j", h.armijo_j},
                        {"cpu_seconds", Num(h.cpu_seconds)}});
  }
  rec["history"] = hist;
  if (with_map) rec["s_map"] = SMap(cp);
  std::ofstream(Cat(out_dir, "/seed", seed, "_", name, ".json")) << rec.dump() << "\n";
  return s;
}

struct Stat {
  std::vector<double> v;
  void Add(double x) { v.push_back(x); }
  std::string Format(int precision = 2) const {
    double mean = 0.0, var = 0.0;
    for (double x : v) mean += x;
    mean /= v.size();
    for (double x : v) var += (x - mean) * (x - mean);
    const double sd = v.size() > 1 ? std::sqrt(var / (v.size() - 1)) : 0.0;
    char buf[160];
    std::snprintf(buf,
                  sizeof buf,
                  "%.*f ± %.*f [%.*f, %.*f]",
                  precision,
                  mean,
                  precision,
                  sd,
                  precision,
                  *std::min_element(v.begin(), v.end()),
                  precision,
                  *std::max_element(v.begin(), v.end()));
    return buf;
  }
};

int Main(int argc, char** argv) {
  std::string out = "results/paper";
  int first = 1, last = 10, channel = 2;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i], value = argv[i + 1];
    if (key == "--out") {
      out = value;
    } else if (key == "--seeds") {
      const auto dash = value.find('-');
      first = std::stoi(value.substr(0, dash));
      last = dash == std::string::npos ? first : std::stoi(value.substr(dash + 1));
    } else if (key == "--channel") {
      channel = std::stoi(value);
    } else {
      std::cerr << "usage: comm_paper_reproduction [--out DIR] [--seeds A-B] [--channel 0|1|2]\n";
      return 2;
    }
  }
  const std::string ch = Cat("channel=", channel);
  std::map<std::string, Stat> a, a56, b;
  std::map<std::string, int> stops;
  for (int seed = first; seed <= last; ++seed) {
    const RunSummary ra = Run(
        "C10", {ch}, seed, {{"max_iterations", "500"}, {"max_armijo_exponent", "50"}}, out, false);
    const RunSummary r56 = Run("C10_56it", {ch}, seed, {{"max_iterations", "56"}}, out, true);
    const RunSummary rb =
        Run("C500", {ch, "C=500,500,500"}, seed, {{"max_iterations", "500"}}, out, false);
    ++stops[Cat(ra.status, " after ", ra.iterations, " it")];
    a["iterations"].Add(ra.iterations);
    a["J"].Add(ra.J);
    a["Jbar"].Add(ra.Jbar);
    a["cpu"].Add(ra.cpu);
    a["theta"].Add(ra.final_theta);
    a56["J0"].Add(r56.J0);
    a56["J20"].Add(r56.J20);
    a56["J"].Add(r56.J);
    a56["Jbar"].Add(r56.Jbar);
    a56["cpu"].Add(r56.cpu);
    a56["theta"].Add(r56.final_theta);
    for (int i = 0; i < 5; ++i) {
      a56[Cat("x", i)].Add(r56.x_final[i]);
      a[Cat("x", i)].Add(ra.x_final[i]);
      b[Cat("x", i)].Add(rb.x_final[i]);
    }
    b["J0"].Add(rb.J0);
    b["J"].Add(rb.J);
    b["Jbar"].Add(rb.Jbar);
    b["cpu"].Add(rb.cpu);
    std::cerr << "seed " << seed << ": A " << ra.status << " it " << ra.iterations << " J " << ra.J
              << " Jbar " << ra.Jbar << " | A56 J " << r56.J << " Jbar " << r56.Jbar << " | B J "
              << rb.J << " Jbar " << rb.Jbar << "\n";
  }
  std::ostringstream t;
  const int n = last - first + 1;
  t << "| quantity | paper | OCPBench, " << n << " channel seeds (" << first << "-" << last
    << "): mean ± sd [min, max] |\n|---|---|---|\n";
  auto row = [&](const std::string& q, const std::string& paper, const std::string& ours) {
    t << "| " << q << " | " << paper << " | " << ours << " |\n";
  };
  auto pos = [](std::map<std::string, Stat>& m, int i, int j) {
    return Cat("(", m[Cat("x", i)].Format(2), ", ", m[Cat("x", j)].Format(2), ")");
  };
  row("C = (10, 50, 10): initial J", "2.3872e5", a56["J0"].Format(2));
  row("J after 20 iterations", "799.63", a56["J20"].Format(2));
  row("J after 56 iterations", "565.13 (stopped: Armijo j > 50)", a56["J"].Format(2));
  row("Jbar after 56 iterations", "475.10", a56["Jbar"].Format(2));
  row("x1(tf) after 56 iterations", "(9.8, 5)", pos(a56, 0, 1));
  row("x2(tf) after 56 iterations", "(0.2, -0.8)", pos(a56, 2, 3));
  row("x3(tf) after 56 iterations", "149.7", a56["x4"].Format(2));
  row("theta after 56 iterations", "not reported", a56["theta"].Format(1));
  row("CPU s for 56 iterations (this machine, shared)", "0.83", a56["cpu"].Format(4));
  std::string stop_text;
  for (const auto& [k, c] : stops) stop_text += Cat(stop_text.empty() ? "" : "; ", k, " (", c, ")");
  row("paper's stopping rule: how it stopped", "Armijo j > 50 after 56", stop_text);
  row("iterations at the stopping rule", "56", a["iterations"].Format(0));
  row("J at the stopping rule", "565.13", a["J"].Format(2));
  row("Jbar at the stopping rule", "475.10", a["Jbar"].Format(2));
  row("x1(tf) at the stopping rule", "(9.8, 5)", pos(a, 0, 1));
  row("x2(tf) at the stopping rule", "(0.2, -0.8)", pos(a, 2, 3));
  row("x3(tf) at the stopping rule", "149.7", a["x4"].Format(2));
  row("theta at the stopping rule", "not reported", a["theta"].Format(1));
  row("C = 500: initial J", "1.1913e7", b["J0"].Format(0));
  row("C = 500: Jbar after 500 iterations", "497.04", b["Jbar"].Format(2));
  row("C = 500: J after 500 iterations", "not reported", b["J"].Format(2));
  row("C = 500: x1(tf)", "(9.99, 5)", pos(b, 0, 1));
  row("C = 500: x2(tf)", "(-0.08, -0.68)", pos(b, 2, 3));
  row("C = 500: x3(tf)", "149.99", b["x4"].Format(2));
  row("C = 500: CPU s for 500 iterations (this machine, shared)", "7.14", b["cpu"].Format(3));
  std::ofstream(out + "/table.md") << t.str();
  std::cout << t.str();
  return 0;
}

}  // namespace
}  // namespace ocpb

int main(int argc, char** argv) { return ocpb::Main(argc, argv); }
