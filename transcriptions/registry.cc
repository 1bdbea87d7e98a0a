#include "transcriptions/registry.h"

#include <stdexcept>
#include <type_traits>
#include <utility>

#include "core/named_registry.h"
#include "transcriptions/euler.h"
#include "transcriptions/hermite_simpson.h"
#include "transcriptions/lgr.h"
#include "transcriptions/radau_nodes.h"
#include "transcriptions/single_shooting.h"
#include "transcriptions/trapezoid.h"

namespace ocpb {
namespace {

OptionBinding<TranscriptionOptions> ScalingOnly(const std::string& owner) {
  OptionBinding<TranscriptionOptions> b(owner);
  BindScalingOptions(&b);
  return b;
}

// The h-refinement schemes: scaling and mesh refinement options.
OptionBinding<TranscriptionOptions> ScalingAndMesh(const std::string& owner) {
  OptionBinding<TranscriptionOptions> b = ScalingOnly(owner);
  BindMeshOptions(&b, MeshRefinementKind::kH);
  return b;
}

std::vector<TranscriptionInfo> BuildTranscriptions() {
  std::vector<TranscriptionInfo> list;
  // [transcriptions] one entry per transcription, in the order `ocpbench list` prints them.
  list.push_back(MakeTranscriptionInfo(
      "euler",
      "forward Euler: x_k and piecewise-constant u_k as variables, the Hamiltonian descent's "
      "discrete problem (order 1)",
      [] { return std::make_unique<EulerTranscription>(); },
      ScalingOnly("euler")));
  list.push_back(MakeTranscriptionInfo(
      "trapezoid",
      "trapezoidal collocation, piecewise-linear controls (order 2)",
      [] { return std::make_unique<TrapezoidTranscription>(); },
      ScalingAndMesh("trapezoid")));
  list.push_back(MakeTranscriptionInfo(
      "hermite-simpson",
      "Hermite-Simpson collocation, separated form, quadratic controls (order 4)",
      [] { return std::make_unique<HermiteSimpsonTranscription>(); },
      ScalingAndMesh("hermite-simpson"),
      [](const TranscriptionOptions&) { return 2; }));
  {
    OptionBinding<TranscriptionOptions> b("lgr");
    b.Integer("degree",
              &TranscriptionOptions::degree,
              "collocation points per interval K (order 2K - 1)",
              OptionBounds::Closed(1, kMaxRadauPoints));
    BindScalingOptions(&b);
    BindMeshOptions(&b, MeshRefinementKind::kPh);
    list.push_back(MakeTranscriptionInfo(
        "lgr",
        "Legendre-Gauss-Radau collocation, --degree points per interval (order 2K-1)",
        [] { return std::make_unique<LgrTranscription>(); },
        std::move(b),
        [](const TranscriptionOptions& o) { return o.degree; }));
  }
  list.push_back(MakeTranscriptionInfo(
      "single-shooting",
      "controls only, piecewise constant; cost by forward Euler simulation, gradient by the "
      "discrete adjoint (RK4 with --integrator rk4)",
      [] { return std::make_unique<SingleShooting>(); },
      ScalingOnly("single-shooting")));
  list.back().takes_free_final_time = false;     // the horizon is fixed by its simulation
  list.back().takes_free_initial_state = false;  // it simulates from x0
  list.back().takes_state_bounds = false;        // its states are not variables
  list.back().takes_boundary_constraints = false;
  return list;
}

NamedRegistry<TranscriptionInfo>& Registry() {
  static NamedRegistry<TranscriptionInfo> registry("transcription", BuildTranscriptions);
  return registry;
}

void SetScale(Vec* target, const OptionValue& v) {
  const std::vector<double>& values = v.vector();
  *target = Eigen::Map<const Vec>(values.data(), static_cast<Eigen::Index>(values.size()));
}

OptionValue ScaleValue(const Vec& v) {
  if (v.size() == 0) return OptionValue();
  return std::vector<double>(v.data(), v.data() + v.size());
}

}  // namespace

TranscriptionOptions TranscriptionInfo::Configure(const OptionMap& given) const {
  TranscriptionOptions out;
  if (configure) {
    configure(given, &out);
  } else if (!given.empty()) {
    throw std::invalid_argument(name + ": unknown option '" + given.begin()->first +
                                "' (valid: none)");
  }
  return out;
}

int TranscriptionInfo::PointsPerInterval(const OptionMap& given) const {
  return points_per_interval ? points_per_interval(Configure(given)) : 1;
}

void BindScalingOptions(OptionBinding<TranscriptionOptions>* binding) {
  binding->Custom(
      [] {
        OptionSpec s;
        s.name = "objective_scale";
        s.type = OptionType::kNumber;
        s.doc = "the NLP minimizes this factor times J (NlpScaling::objective)";
        s.default_value = 1.0;
        s.bounds = OptionBounds::Above(0);
        return s;
      }(),
      [](TranscriptionOptions* o, const OptionValue& v) { o->scaling.objective = v.number(); },
      [](const TranscriptionOptions& o) { return OptionValue(o.scaling.objective); });
  for (const bool state : {true, false}) {
    OptionSpec s;
    s.name = state ? "state_scale" : "control_scale";
    s.type = OptionType::kVector;
    s.doc = state ? "per-state scales: x_i is stored as x_i / scale_i, its defects divided too"
                  : "per-control scales: u_j is stored as u_j / scale_j";
    s.unset_doc = "all ones";
    s.bounds = OptionBounds::Above(0);
    binding->Custom(
        std::move(s),
        [state](TranscriptionOptions* o, const OptionValue& v) {
          SetScale(state ? &o->scaling.state : &o->scaling.control, v);
        },
        [state](const TranscriptionOptions& o) {
          return ScaleValue(state ? o.scaling.state : o.scaling.control);
        });
  }
}

void BindMeshOptions(OptionBinding<TranscriptionOptions>* binding, MeshRefinementKind kind) {
  const bool h = kind == MeshRefinementKind::kH;
  binding->NestedMember(
      "mesh_tolerance",
      &TranscriptionOptions::mesh,
      &MeshRefinementOptions::tolerance,
      h ? "adaptive h-refinement until every interval's error estimate (mesh_estimate) "
          "is <= this; 0: off, one solve on the given grid"
        : "adaptive ph-refinement (raise an interval's degree, or split it) until "
          "every interval's error estimate (mesh_estimate) is <= this; 0: off, one "
          "solve on the given grid",
      OptionBounds::AtLeast(0));
  binding->NestedMember("mesh_max_iterations",
                        &TranscriptionOptions::mesh,
                        &MeshRefinementOptions::max_iterations,
                        "at most this many meshes are solved (the given grid is the first)",
                        OptionBounds::AtLeast(1));
  binding->NestedMember(
      "mesh_max_nodes",
      &TranscriptionOptions::mesh,
      &MeshRefinementOptions::max_nodes,
      h ? "a refined mesh with more nodes (N + 1) than this is not solved; refinement "
          "stops on the last mesh"
        : "a refined mesh with more collocation points + 1 (the sum of the interval "
          "degrees + 1) than this is not solved; refinement stops on the last mesh",
      OptionBounds::AtLeast(2));
  const std::string own = h ? "defect" : "interpolation";
  {
    OptionSpec s;
    s.name = "mesh_estimate";
    s.type = OptionType::kEnum;
    s.choices = {own, "simulation"};
    s.default_value = own;
    s.doc = h ? "the local error estimate: defect (Betts' scaled integral of the state "
                "interpolant's defect) or simulation (RK4 from each interval's start state with "
                "the interpolated control, against the collocated states)"
              : "the local error estimate: interpolation (Patterson-Hager-Rao: the state "
                "polynomial against the quadrature of f at K + 1 points) or simulation (RK4 from "
                "each interval's start state with the interpolated control, against the "
                "collocated states)";
    binding->Custom(
        std::move(s),
        [](TranscriptionOptions* o, const OptionValue& v) {
          o->mesh.estimate = v.text() == "simulation" ? MeshErrorEstimate::kSimulation
                                                      : MeshErrorEstimate::kScheme;
        },
        [own](const TranscriptionOptions& o) {
          return OptionValue(o.mesh.estimate == MeshErrorEstimate::kSimulation ? "simulation"
                                                                               : own);
        });
  }
  binding->Custom(
      [] {
        OptionSpec s;
        s.name = "mesh_warm_multipliers";
        s.type = OptionType::kBool;
        s.doc =
            "start each refined mesh from the previous solution's multipliers too (costates "
            "interpolated and mapped to the new defects; Ipopt's warm start; NLopt takes none); "
            "false: controls and states only";
        s.default_value = MeshRefinementOptions{}.warm_multipliers;
        return s;
      }(),
      [](TranscriptionOptions* o, const OptionValue& v) { o->mesh.warm_multipliers = v.boolean(); },
      [](const TranscriptionOptions& o) { return OptionValue(o.mesh.warm_multipliers); });
  if (h) {
    binding->NestedMember("mesh_max_new_points",
                          &TranscriptionOptions::mesh,
                          &MeshRefinementOptions::max_new_points,
                          "at most this many nodes added to one interval per refinement",
                          OptionBounds::AtLeast(1));
    return;
  }
  binding->NestedMember("mesh_min_degree",
                        &TranscriptionOptions::mesh,
                        &MeshRefinementOptions::min_degree,
                        "ph: the degree of the pieces of a split interval, and the least degree "
                        "lowering goes down to",
                        OptionBounds::Closed(1, kMaxRadauPoints - 1));
  binding->NestedMember(
      "mesh_max_degree",
      &TranscriptionOptions::mesh,
      &MeshRefinementOptions::max_degree,
      "ph: an interval whose predicted degree exceeds this is split instead of raised "
      "(>= mesh_min_degree)",
      OptionBounds::Closed(1, kMaxRadauPoints - 1));
  binding->Custom(
      [] {
        OptionSpec s;
        s.name = "mesh_reduce";
        s.type = OptionType::kBool;
        s.doc =
            "ph: merge adjacent intervals and lower degrees where the tolerance is met with room "
            "to spare";
        s.default_value = MeshRefinementOptions{}.reduce;
        return s;
      }(),
      [](TranscriptionOptions* o, const OptionValue& v) { o->mesh.reduce = v.boolean(); },
      [](const TranscriptionOptions& o) { return OptionValue(o.mesh.reduce); });
}

TranscriptionInfo MakeTranscriptionInfo(
    std::string name,
    std::string description,
    std::function<std::unique_ptr<Transcription>()> make,
    OptionBinding<TranscriptionOptions> binding,
    std::function<int(const TranscriptionOptions&)> points_per_interval) {
  TranscriptionInfo info;
  info.name = std::move(name);
  info.description = std::move(description);
  info.make = std::move(make);
  info.options = binding.schema();
  info.configure = [binding = std::move(binding), owner = info.name](const OptionMap& given,
                                                                     TranscriptionOptions* out) {
    *out = binding.Apply(given, *out);
    // The rules between options (mesh_min_degree <= mesh_max_degree).
    std::string why;
    if (!out->mesh.IsValid(&why)) throw std::invalid_argument(owner + ": " + why);
  };
  info.points_per_interval = std::move(points_per_interval);
  return info;
}

const std::vector<TranscriptionInfo>& Transcriptions() { return Registry().All(); }

const TranscriptionInfo& FindTranscription(const std::string& name) {
  return Registry().Find(name);
}

void RegisterTranscription(TranscriptionInfo info) {
  Registry().Add("RegisterTranscription", std::move(info), [](const TranscriptionInfo& t) {
    if (!t.make) {
      throw std::invalid_argument("RegisterTranscription: '" + t.name + "' has no make function");
    }
  });
}

}  // namespace ocpb
