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
  BindMeshOptions(&b);
  return b;
}

// One option bound to a number or integer field of TranscriptionOptions::mesh.
template <class T>
void BindMeshField(OptionBinding<TranscriptionOptions>* binding,
                   const char* name,
                   T MeshRefinementOptions::*field,
                   std::string doc,
                   OptionBounds bounds) {
  OptionSpec s;
  s.name = name;
  s.type = std::is_same_v<T, double> ? OptionType::kNumber : OptionType::kInteger;
  s.doc = std::move(doc);
  s.default_value = MeshRefinementOptions{}.*field;
  s.bounds = bounds;
  binding->Custom(
      std::move(s),
      [field](TranscriptionOptions* o, const OptionValue& v) {
        if constexpr (std::is_same_v<T, double>) {
          o->mesh.*field = v.number();
        } else {
          o->mesh.*field = static_cast<int>(v.integer());
        }
      },
      [field](const TranscriptionOptions& o) { return OptionValue(o.mesh.*field); });
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
  list.back().takes_free_final_time = false;  // the horizon is fixed by its simulation
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

void BindMeshOptions(OptionBinding<TranscriptionOptions>* binding) {
  BindMeshField(binding,
                "mesh_tolerance",
                &MeshRefinementOptions::tolerance,
                "adaptive h-refinement until every interval's error estimate (Betts' scaled "
                "integral of the collocation interpolant's defect) is <= this; 0: off, one "
                "solve on the given grid",
                OptionBounds::AtLeast(0));
  BindMeshField(binding,
                "mesh_max_iterations",
                &MeshRefinementOptions::max_iterations,
                "at most this many meshes are solved (the given grid is the first)",
                OptionBounds::AtLeast(1));
  BindMeshField(binding,
                "mesh_max_nodes",
                &MeshRefinementOptions::max_nodes,
                "a refined mesh with more nodes (N + 1) than this is not solved; refinement "
                "stops on the last mesh",
                OptionBounds::AtLeast(2));
  BindMeshField(binding,
                "mesh_max_new_points",
                &MeshRefinementOptions::max_new_points,
                "at most this many nodes added to one interval per refinement",
                OptionBounds::AtLeast(1));
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
  info.configure = [binding = std::move(binding)](const OptionMap& given,
                                                  TranscriptionOptions* out) {
    *out = binding.Apply(given, *out);
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
