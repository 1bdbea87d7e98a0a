// The option schemas of the Hamiltonian family's registered methods (one binding, three sets of
// defaults).
#include <cctype>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "core/invalid.h"
#include "core/option_binding.h"
#include "solvers/hamiltonian_family.h"

namespace ocpb {
namespace {

using Options = HamiltonianFamilyOptions;

// The presets as types, so that each registered method's schema shows its own defaults.
struct ProximalPreset : Options {
  ProximalPreset() { static_cast<Options&>(*this) = HamiltonianFamily::Proximal(); }
};
struct AugmentedLagrangianPreset : Options {
  AugmentedLagrangianPreset() {
    static_cast<Options&>(*this) = HamiltonianFamily::AugmentedLagrangian();
  }
};
struct PolishPreset : Options {
  PolishPreset() { static_cast<Options&>(*this) = HamiltonianFamily::Polished(); }
};

template <class O>
OptionBinding<O> MakeBinding(const std::string& owner) {
  OptionBinding<O> t(owner);
  t.Number("alpha", &O::alpha, "Armijo sufficient-decrease constant", OptionBounds::Open(0, 1));
  t.Number("beta", &O::beta, "Armijo step reduction", OptionBounds::Open(0, 1));
  t.Integer("max_armijo_exponent",
            &O::max_armijo_exponent,
            "largest Armijo exponent j tried",
            OptionBounds::AtLeast(0));
  t.Bool("armijo_prefilter",
         &O::armijo_prefilter,
         "reject Armijo trials by lower bounds (same iterates, less work)");
  t.Integer("max_iterations",
            &O::max_iterations,
            "descent steps at most, over every phase and outer iteration",
            OptionBounds::AtLeast(0));
  t.Number("relative_theta_tolerance",
           &O::relative_theta_tolerance,
           "penalty form: stop when |theta| <= this (1 + |J|) (0: off)",
           OptionBounds::AtLeast(0));
  t.Number("max_cpu_seconds",
           &O::max_cpu_seconds,
           "CPU time limit of the whole solve (inf: none)",
           OptionBounds::Above(0).WithInfinity());
  t.OptionalNumber("path_penalty",
                   &O::path_penalty,
                   "rho of the reformulation's path penalty rho max(0, c)^2",
                   OptionBounds::Above(0),
                   "the problem's own default");
  t.OptionalNumber("regularization",
                   &O::regularization,
                   "eps of the reformulation's control regularization eps |u|^2",
                   OptionBounds::Above(0),
                   "the problem's own default");
  t.template Enum<Options::Direction>(
      "direction",
      &O::direction,
      {{"paper", Options::Direction::kPaper}, {"proximal", Options::Direction::kProximal}},
      "the descent's direction: the paper's u* - u, or Sakawa-Shindo's proximal one");
  t.template Enum<Options::Scheme>(
      "scheme",
      &O::scheme,
      {{"euler", Options::Scheme::kEuler},
       {"rk2", Options::Scheme::kRk2},
       {"rk4", Options::Scheme::kRk4}},
      "the descent's discretization: forward Euler, or Heun / classical RK4 with one control per "
      "stage and the exact transformed adjoint (the polish there: projected Newton on the stage "
      "controls)");
  t.NestedMember("proximal_eps",
                 &Options::proximal,
                 &ProximalSchedule::initial_eps,
                 "proximal direction: eps of the first iteration",
                 OptionBounds::Above(0));
  t.NestedMember("proximal_growth",
                 &Options::proximal,
                 &ProximalSchedule::growth,
                 "proximal direction: eps factor after a full Armijo step",
                 OptionBounds::AtLeast(1));
  t.NestedMember("proximal_min_eps",
                 &Options::proximal,
                 &ProximalSchedule::min_eps,
                 "proximal direction: smallest eps",
                 OptionBounds::Above(0));
  t.NestedMember("proximal_max_eps",
                 &Options::proximal,
                 &ProximalSchedule::max_eps,
                 "proximal direction: largest eps (inf: the paper's direction allowed)",
                 OptionBounds::Above(0).WithInfinity());
  t.template Enum<Options::PathConstraints>(
      "path",
      &O::path,
      {{"reformulation", Options::PathConstraints::kReformulation},
       {"augmented-lagrangian", Options::PathConstraints::kAugmentedLagrangian}},
      "path constraints: the problem's penalty reformulation, or the outer loop's multipliers");
  using AL = AugmentedLagrangianRule;
  t.NestedMember("al_initial_penalty",
                 &Options::augmented_lagrangian,
                 &AL::initial_penalty,
                 "outer loop: rho_0",
                 OptionBounds::Above(0));
  t.NestedMember(
      "al_penalty_growth",
      &Options::augmented_lagrangian,
      &AL::penalty_growth,
      "outer loop: rho factor when the infeasibility did not fall below eta (the rk2/rk4 "
      "polish's loop: when max |psi| did not fall to a quarter)",
      OptionBounds::Above(1));
  t.NestedMember("al_max_penalty",
                 &Options::augmented_lagrangian,
                 &AL::max_penalty,
                 "outer loop: largest rho",
                 OptionBounds::Above(0));
  t.NestedMember("al_initial_feasibility",
                 &Options::augmented_lagrangian,
                 &AL::initial_feasibility,
                 "outer loop: eta_0",
                 OptionBounds::Above(0));
  t.NestedMember("al_feasibility_tolerance",
                 &Options::augmented_lagrangian,
                 &AL::feasibility_tolerance,
                 "outer loop: converged when max |psi| and max c+ are below this",
                 OptionBounds::Above(0));
  t.NestedMember("al_initial_inner_tolerance",
                 &Options::augmented_lagrangian,
                 &AL::initial_inner_tolerance,
                 "outer loop: omega_0, relative inner |theta| tolerance",
                 OptionBounds::Above(0));
  t.NestedMember("al_final_inner_tolerance",
                 &Options::augmented_lagrangian,
                 &AL::final_inner_tolerance,
                 "outer loop: the last inner solves' relative |theta| tolerance",
                 OptionBounds::Above(0));
  t.NestedMember("al_max_outer_iterations",
                 &Options::augmented_lagrangian,
                 &AL::max_outer_iterations,
                 "outer loop: outer iterations at most",
                 OptionBounds::AtLeast(1));
  t.NestedMember("al_max_inner_iterations",
                 &Options::augmented_lagrangian,
                 &AL::max_inner_iterations,
                 "outer loop: descent steps per outer iteration at most",
                 OptionBounds::AtLeast(1));
  t.Number("free_time_initial_fraction",
           &O::free_time_initial_fraction,
           "free final time: the first T step moves T by at most this fraction of T - t0",
           OptionBounds::Above(0));
  t.Bool("polish",
         &O::polish,
         "Newton after the descent: on the Euler maximum principle (scheme euler), projected "
         "truncated Newton on the stage controls (rk2, rk4)");
  t.Number("polish_switch",
           &O::polish_switch,
           "polish: the descent hands over at |theta| <= this (1 + |J|) or max_iterations",
           OptionBounds::Above(0));
  t.Integer("newton_max_iterations",
            &O::newton_max_iterations,
            "polish: Newton steps per attempt at most (rk2/rk4: per Newton solve)",
            OptionBounds::AtLeast(0));
  t.Number("newton_tolerance",
           &O::newton_tolerance,
           "polish: Newton converged at ||F||_inf <= this (rk2/rk4: the projected residual, and "
           "max |psi| in the hard form)",
           OptionBounds::Above(0));
  t.Integer("newton_stall_steps",
            &O::newton_stall_steps,
            "polish: an attempt ends after this many Newton steps in a row of length <= 1/256 "
            "(0: off; not used by the rk2/rk4 polish)",
            OptionBounds::AtLeast(0));
  t.Number("newton_backtrack",
           &O::newton_backtrack,
           "polish: Newton's line search tries steps 1, b, b^2, ... (b this)",
           OptionBounds::Open(0, 1));
  t.Number("newton_sufficient_decrease",
           &O::newton_sufficient_decrease,
           "polish: Armijo constant c of Newton's merit 1/2 ||F||^2 (rk2/rk4: of J)",
           OptionBounds::Open(0, 0.5));
  t.template Enum<IndirectNewtonOptions::LinearSolver>(
      "newton_linear_solver",
      &O::newton_linear_solver,
      {{"riccati", IndirectNewtonOptions::LinearSolver::kRiccati},
       {"klu", IndirectNewtonOptions::LinearSolver::kKlu},
       {"umfpack", IndirectNewtonOptions::LinearSolver::kUmfpack}},
      "polish: Newton's linear solver (the Riccati sweep, KLU its fallback; or a sparse LU)");
  t.Integer("polish_attempts",
            &O::polish_attempts,
            "polish: Newton attempts at most (the descent continues between them)",
            OptionBounds::AtLeast(1));
  t.Bool("polish_constant_costate_start",
         &O::polish_constant_costate_start,
         "polish: start Newton with each integrator state's costate constant, solved from that "
         "state's terminal condition");
  t.Integer("polish_coarse_levels",
            &O::polish_coarse_levels,
            "polish: grid sequencing, the polish first on every 2^L-th node and Newton on each "
            "finer grid from there (L at most this; 0: off)",
            OptionBounds::AtLeast(0));
  t.Integer("polish_coarse_min_intervals",
            &O::polish_coarse_min_intervals,
            "polish: grid sequencing's coarsest grid keeps at least this many intervals",
            OptionBounds::AtLeast(1));
  return t;
}

template <class O>
const OptionBinding<O>& Binding(const char* owner) {
  static const OptionBinding<O> binding = MakeBinding<O>(owner);
  return binding;
}

}  // namespace

const char* HamiltonianFamily::Name(Preset preset) {
  switch (preset) {
    case Preset::kProximal:
      return "hamiltonian-proximal";
    case Preset::kAugmentedLagrangian:
      return "hamiltonian-al";
    case Preset::kPolish:
      break;
  }
  return "hamiltonian-polish";
}

const char* HamiltonianFamily::Description(Preset preset) {
  switch (preset) {
    case Preset::kProximal:
      return "Hamiltonian family: the descent with Sakawa-Shindo's proximal direction (hard "
             "terminal form by an augmented-Lagrangian loop, free final time)";
    case Preset::kAugmentedLagrangian:
      return "Hamiltonian family: the descent inside an augmented-Lagrangian loop for terminal "
             "and path constraints (free final time)";
    case Preset::kPolish:
      break;
  }
  return "Hamiltonian family: the descent, then Newton on the Euler maximum principle from its "
         "states and fitted costates (both phases in the record; free final time)";
}

HamiltonianFamily::Options HamiltonianFamily::Defaults(Preset preset) {
  switch (preset) {
    case Preset::kProximal:
      return Proximal();
    case Preset::kAugmentedLagrangian:
      return AugmentedLagrangian();
    case Preset::kPolish:
      break;
  }
  return Polished();
}

const OptionSchema& HamiltonianFamily::Schema(Preset preset) {
  switch (preset) {
    case Preset::kProximal:
      return Binding<ProximalPreset>(Name(preset)).schema();
    case Preset::kAugmentedLagrangian:
      return Binding<AugmentedLagrangianPreset>(Name(preset)).schema();
    case Preset::kPolish:
      break;
  }
  return Binding<PolishPreset>(Name(preset)).schema();
}

HamiltonianFamily::Options HamiltonianFamily::ApplyOptions(Preset preset,
                                                           const OptionMap& options,
                                                           const Options& base) {
  Options o;
  switch (preset) {
    case Preset::kProximal: {
      ProximalPreset b;
      static_cast<Options&>(b) = base;
      o = Binding<ProximalPreset>(Name(preset)).Apply(options, b);
      break;
    }
    case Preset::kAugmentedLagrangian: {
      AugmentedLagrangianPreset b;
      static_cast<Options&>(b) = base;
      o = Binding<AugmentedLagrangianPreset>(Name(preset)).Apply(options, b);
      break;
    }
    case Preset::kPolish: {
      PolishPreset b;
      static_cast<Options&>(b) = base;
      o = Binding<PolishPreset>(Name(preset)).Apply(options, b);
      break;
    }
  }
  std::string error;
  if (!o.IsValid(&error)) throw std::invalid_argument(std::string(Name(preset)) + ": " + error);
  return o;
}

bool HamiltonianFamilyOptions::IsValid(std::string* error) const {
  ProximalPreset p;
  static_cast<Options&>(p) = *this;
  if (!Binding<ProximalPreset>(HamiltonianFamily::Name(HamiltonianFamily::Preset::kProximal))
           .Check(p, error)) {
    return false;
  }
  std::string why;
  if (!proximal.IsValid(&why)) return Invalid(error, "proximal: " + why);
  if (!augmented_lagrangian.IsValid(&why)) {
    // The rule names its fields; the family's options are those names with "al_" before them.
    std::string named;
    for (size_t i = 0; i < why.size(); ++i) {
      const bool word_start =
          i == 0 || !(std::isalnum(static_cast<unsigned char>(why[i - 1])) || why[i - 1] == '_');
      if (word_start && (std::islower(static_cast<unsigned char>(why[i]))) &&
          why.find('_', i) < why.find(' ', i)) {
        named += "al_";
      }
      named += why[i];
    }
    return Invalid(error, "augmented-Lagrangian options: " + named);
  }
  return true;
}

}  // namespace ocpb
