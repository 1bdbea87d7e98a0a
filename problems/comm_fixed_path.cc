#include "problems/comm_fixed_path.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/invalid.h"

namespace ocpb {
namespace {

// "C1", "k3": built with a stream (GCC 12 warns falsely on "C" + std::to_string(i)).
std::string IndexedName(const char* name, int i) {
  std::ostringstream os;
  os << name << i;
  return os.str();
}

}  // namespace

// ---- PlanarPath ----------------------------------------------------------------------------

PlanarPath::PlanarPath(const std::vector<Eigen::Vector2d>& waypoints, double fillet)
    : waypoints_(waypoints), fillet_(fillet) {
  const int n = static_cast<int>(waypoints.size());
  if (n < 2) throw std::invalid_argument("path: need at least 2 waypoints");
  if (!(fillet >= 0.0) || !std::isfinite(fillet)) {
    throw std::invalid_argument("fillet: must be finite and >= 0");
  }
  std::vector<Eigen::Vector2d> dir(n - 1);
  std::vector<double> len(n - 1);
  for (int i = 0; i + 1 < n; ++i) {
    if (!waypoints[i].allFinite()) throw std::invalid_argument("path: waypoints must be finite");
    const Eigen::Vector2d d = waypoints[i + 1] - waypoints[i];
    len[i] = d.norm();
    if (!(len[i] > 1e-9)) throw std::invalid_argument("path: consecutive waypoints must differ");
    dir[i] = d / len[i];
  }
  // Cut-back at each interior corner.
  std::vector<double> cut(n, 0.0), turn_angle(n, 0.0), turn_sign(n, 1.0);
  for (int i = 1; i + 1 < n; ++i) {
    const Eigen::Vector2d& a = dir[i - 1];
    const Eigen::Vector2d& b = dir[i];
    const double cross = a[0] * b[1] - a[1] * b[0];
    const double phi = std::atan2(std::abs(cross), a.dot(b));
    if (phi > M_PI - 1e-6) throw std::invalid_argument("path: a corner turns back on itself");
    turn_angle[i] = phi;
    turn_sign[i] = cross >= 0.0 ? 1.0 : -1.0;
    cut[i] = fillet * std::tan(0.5 * phi);
  }
  for (int i = 0; i + 1 < n; ++i) {
    if (cut[i] > 0.5 * len[i] + 1e-12 || cut[i + 1] > 0.5 * len[i] + 1e-12) {
      throw std::invalid_argument("fillet: radius too large for the corners of segment " +
                                  std::to_string(i) + " (cut-back exceeds half its length)");
    }
  }
  double s = 0.0;
  for (int i = 0; i + 1 < n; ++i) {
    Piece line;
    line.arc = false;
    line.s0 = s;
    line.start = waypoints[i] + cut[i] * dir[i];
    line.direction = dir[i];
    line.length = len[i] - cut[i] - cut[i + 1];
    pieces_.push_back(line);
    s += line.length;
    const int v = i + 1;  // the corner at the end of this segment
    if (v + 1 < n && fillet > 0.0 && turn_angle[v] > 1e-12) {
      Piece arc;
      arc.arc = true;
      arc.s0 = s;
      arc.length = fillet * turn_angle[v];
      arc.turn = turn_sign[v];
      const Eigen::Vector2d& a = dir[i];
      const Eigen::Vector2d normal = arc.turn * Eigen::Vector2d(-a[1], a[0]);  // toward the turn
      const Eigen::Vector2d begin = waypoints[v] - cut[v] * a;
      arc.center = begin + fillet * normal;
      arc.angle0 = std::atan2(-normal[1], -normal[0]);
      pieces_.push_back(arc);
      s += arc.length;
    }
  }
  length_ = s;
}

void PlanarPath::Evaluate(double sigma,
                          Eigen::Vector2d* q,
                          Eigen::Vector2d* dq,
                          Eigen::Vector2d* ddq) const {
  // The piece containing sigma (the first or last line beyond the ends).
  size_t i = 0;
  while (i + 1 < pieces_.size() && sigma >= pieces_[i + 1].s0) ++i;
  const Piece& p = pieces_[i];
  const double ds = sigma - p.s0;
  if (!p.arc) {
    if (q) *q = p.start + ds * p.direction;
    if (dq) *dq = p.direction;
    if (ddq) ddq->setZero();
    return;
  }
  const double angle = p.angle0 + p.turn * ds / fillet_;
  const double c = std::cos(angle), s = std::sin(angle);
  if (q) *q = p.center + fillet_ * Eigen::Vector2d(c, s);
  if (dq) *dq = p.turn * Eigen::Vector2d(-s, c);
  if (ddq) *ddq = -(1.0 / fillet_) * Eigen::Vector2d(c, s);
}

// ---- CommFixedPath ----------------------------------------------------------------------------

bool CommFixedPath::Options::IsValid(std::string* error) const {
  if (!(bits >= 0.0) || !std::isfinite(bits)) return Invalid(error, "c must be finite and >= 0");
  if (!(tf > 0.0) || !std::isfinite(tf)) return Invalid(error, "tf must be finite and > 0");
  if (!(umax > 0.0) || !std::isfinite(umax)) return Invalid(error, "umax must be finite and > 0");
  if (!(rmax > 0.0) || !std::isfinite(rmax)) return Invalid(error, "Rmax must be finite and > 0");
  for (int i = 0; i < 3; ++i) {
    if (!(penalty[i] > 0.0) || !std::isfinite(penalty[i])) {
      return Invalid(error, IndexedName("C", i + 1) + " must be finite and > 0");
    }
  }
  return power.IsValid(error);
}

CommFixedPath::CommFixedPath(const Options& options,
                             std::shared_ptr<const PlanarPath> path,
                             std::shared_ptr<const ChannelQuality> channel)
    : options_(options),
      inv_k_(1.0 / options.power.K()),
      path_(std::move(path)),
      channel_(std::move(channel)) {
  std::string error;
  if (!options_.IsValid(&error)) throw std::invalid_argument("comm-fixed-path: " + error);
  if (!path_) throw std::invalid_argument("comm-fixed-path: path must not be null");
  if (!channel_) throw std::invalid_argument("comm-fixed-path: channel must not be null");
  SetDimensions(3, 2, 3, 0);
  SetHorizon(0.0, options_.tf);
  SetInitialState(Vec::Zero(3));
  SetTerminalWeights(options_.penalty);
  SetControlSet(ControlSet::Box(Eigen::Vector2d(-options_.umax, 0.0),
                                Eigen::Vector2d(options_.umax, options_.rmax)));
}

void CommFixedPath::MinimizeHamiltonian(double, ConstVecRef x, ConstVecRef p, VecRef u) const {
  const double a = std::abs(p[1]);
  const double nv = options_.power.SmoothNorm(x[1] * x[1]);
  const double r = options_.power.AccelerationMagnitude(a, nv, options_.umax);
  u[0] = p[1] > 0.0 ? -r : (p[1] < 0.0 ? r : (a == 0.0 ? 0.0 : a));
  Eigen::Vector2d q;
  path_->Evaluate(x[0], &q, nullptr, nullptr);
  double s = 0.0;
  channel_->Evaluate(q, &s, nullptr, nullptr);
  u[1] = options_.power.Rate(p[2], s, options_.rmax);
}

ProblemInfo CommFixedPathProblemInfo() {
  ProblemInfo p;
  p.name = "comm-fixed-path";
  p.description =
      "speed and transmission rate co-optimized along a fixed path S -> W -> D over a predicted "
      "channel (the ACC 2016 paper's predecessor problem)";
  p.parameters = CommParameterSpecs();
  p.parameters.push_back(
      {"W", {7.0, 9.0}, "waypoint of the path S -> W -> D (m), in [0, 50]^2", 0.0, 50.0});
  p.parameters.push_back(
      {"fillet", {2.0}, "radius of the arc rounding the corner at W (m); 0: sharp", 0.0, 100.0});
  // make_for_checks builds the same problem over a path-loss stand-in for the channel.
  auto build = [](const Parameters& params, std::shared_ptr<const ChannelQuality> channel) {
    CommFixedPath::Options o;
    o.bits = params.Scalar("c");
    o.tf = params.Scalar("tf");
    o.umax = params.Scalar("umax");
    o.rmax = params.Scalar("Rmax");
    o.penalty = params.Vector("C");
    o.power = CommPowerFromParameters(params);
    auto path = std::make_shared<PlanarPath>(
        std::vector<Eigen::Vector2d>{params.Vector("S"), params.Vector("W"), params.Vector("D")},
        params.Scalar("fillet"));
    return std::make_unique<CommFixedPath>(o, std::move(path), std::move(channel));
  };
  p.make = [build](const Parameters& params, std::uint64_t seed) -> std::unique_ptr<Ocp> {
    return build(params, MakeCommChannel(params, seed));
  };
  p.make_for_checks = [build](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return build(params, MakeCommChannelForChecks(params));
  };
  p.default_intervals = 400;
  p.uses_seed = true;
  p.tags = {"paper"};
  return p;
}

}  // namespace ocpb
