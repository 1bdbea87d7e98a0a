// IpoptOptions' option table: its named fields and Ipopt's pass-through options, by type.
#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "core/option_binding.h"
#include "solvers/ipopt_adapter.h"

namespace ocpb {
namespace {

OptionType TypeOf(const IpoptOptionSpec& spec) {
  switch (spec.type) {
    case IpoptOptionType::kNumber:
      return OptionType::kNumber;
    case IpoptOptionType::kInteger:
      return OptionType::kInteger;
    case IpoptOptionType::kString:
      break;
  }
  return spec.values.empty() ? OptionType::kText : OptionType::kEnum;
}

// A pass-through option: unset by default (Ipopt's own default), stored in `extra` by type.
void BindPassThrough(OptionBinding<IpoptOptions>* t, const IpoptOptionSpec& ipopt) {
  OptionSpec s;
  s.name = ipopt.name;
  s.type = TypeOf(ipopt);
  s.choices = ipopt.values;
  s.bounds = ipopt.bounds;
  s.doc = "Ipopt option, passed through";
  s.unset_doc = "Ipopt's default";
  const std::string name = ipopt.name;
  const IpoptOptionType type = ipopt.type;
  t->Custom(
      std::move(s),
      [name, type](IpoptOptions* o, const OptionValue& v) {
        IpoptOptionValue value;
        value.name = name;
        value.type = type;
        switch (type) {
          case IpoptOptionType::kNumber:
            value.number = v.number();
            break;
          case IpoptOptionType::kInteger:
            value.integer = static_cast<int>(v.integer());
            break;
          case IpoptOptionType::kString:
            value.text = v.text();
            break;
        }
        auto& extra = o->extra;
        extra.erase(std::remove_if(extra.begin(),
                                   extra.end(),
                                   [&name](const IpoptOptionValue& e) { return e.name == name; }),
                    extra.end());
        extra.push_back(value);
      },
      [name](const IpoptOptions& o) {
        for (const IpoptOptionValue& e : o.extra) {
          if (e.name != name) continue;
          switch (e.type) {
            case IpoptOptionType::kNumber:
              return OptionValue(e.number);
            case IpoptOptionType::kInteger:
              return OptionValue(e.integer);
            case IpoptOptionType::kString:
              return OptionValue(e.text);
          }
        }
        return OptionValue();
      });
}

const OptionBinding<IpoptOptions>& IpoptBinding() {
  static const OptionBinding<IpoptOptions> table = [] {
    using O = IpoptOptions;
    OptionBinding<O> t("ipopt");
    t.Number(
        "tol", &O::tol, "convergence tolerance on the scaled NLP error", OptionBounds::Above(0));
    t.Integer("max_iter", &O::max_iter, "iteration limit", OptionBounds::AtLeast(0));
    t.Number("acceptable_tol",
             &O::acceptable_tol,
             "the 'acceptable' level's tolerance",
             OptionBounds::Above(0));
    t.Integer("acceptable_iter",
              &O::acceptable_iter,
              "consecutive acceptable iterates that end the solve",
              OptionBounds::AtLeast(0));
    t.Number("max_cpu_time", &O::max_cpu_time, "CPU time limit, s", OptionBounds::Above(0));
    t.Text("mu_strategy", &O::mu_strategy, "barrier parameter update", {"monotone", "adaptive"});
    t.Text("hessian_approximation",
           &O::hessian_approximation,
           "auto: exact when the NLP has a Hessian, else limited-memory",
           {"auto", "exact", "limited-memory"});
    t.Text("linear_solver", &O::linear_solver, "the only one in this build", {"mumps"});
    t.Text("nlp_scaling_method",
           &O::nlp_scaling_method,
           "Ipopt's automatic NLP scaling",
           {"none", "gradient-based"});
    t.Number("obj_scaling_factor",
             &O::obj_scaling_factor,
             "Ipopt minimizes this factor times f (finite, nonzero)");
    t.Number("nlp_scaling_max_gradient",
             &O::nlp_scaling_max_gradient,
             "largest gradient max-norm gradient-based scaling leaves alone",
             OptionBounds::Above(0));
    t.Number("warm_start_bound_push",
             &O::warm_start_bound_push,
             "warm-started solves: push of a starting variable or slack into its bounds' "
             "interior (also warm_start_bound_frac, the slacks' push and frac)",
             OptionBounds::Above(0));
    t.Number("warm_start_mult_bound_push",
             &O::warm_start_mult_bound_push,
             "warm-started solves: least starting bound multiplier",
             OptionBounds::Above(0));
    t.Number("warm_start_mu_init",
             &O::warm_start_mu_init,
             "warm-started solves: the barrier parameter they begin with (OCPBench's name; "
             "Ipopt's mu_init for that solve)",
             OptionBounds::Above(0));
    t.Integer("print_level",
              &O::print_level,
              "Ipopt's log: 0 silent, 5 its iteration log",
              OptionBounds::Closed(0, 12));
    for (const IpoptOptionSpec& spec : IpoptOptionTable()) {
      if (!t.schema().Contains(spec.name)) BindPassThrough(&t, spec);
    }
    return t;
  }();
  return table;
}

}  // namespace

bool IpoptOptions::IsValid(std::string* error) const {
  if (!IpoptBinding().Check(*this, error)) return false;
  // The field (not the pass-through option of the same name, which overrides it).
  if (mumps_pivot_order < -1 || mumps_pivot_order > 7) {
    if (error) *error = "ipopt: mumps_pivot_order must be in -1..7 (-1: by problem class)";
    return false;
  }
  if (!(obj_scaling_factor != 0.0)) {
    if (error) *error = "ipopt option 'obj_scaling_factor': must be finite and nonzero";
    return false;
  }
  for (const IpoptOptionValue& v : extra) {
    // Ipopt opens (and truncates) its output file only when the solve starts: a place it cannot
    // open would fail the solve after the work before it.
    if (v.name == "output_file" && !v.text.empty()) {
      std::error_code ec;
      const std::filesystem::path file(v.text);
      const std::filesystem::path folder =
          file.parent_path().empty() ? std::filesystem::path(".") : file.parent_path();
      // A name the system refuses to look up (too long, a loop of links, a file as a folder).
      (void)std::filesystem::status(file, ec);
      if (ec && ec != std::errc::no_such_file_or_directory) {
        if (error) {
          *error = "ipopt option 'output_file': '" + v.text.substr(0, 80) +
                   (v.text.size() > 80 ? "...'" : "'") + ": " + ec.message();
        }
        return false;
      }
      if (std::filesystem::is_directory(file, ec) || !std::filesystem::is_directory(folder, ec)) {
        if (error) {
          *error =
              "ipopt option 'output_file': '" + v.text +
              "' must name a file in an existing folder (it is " +
              (std::filesystem::is_directory(file, ec) ? "a folder)" : "in no folder that exists)");
        }
        return false;
      }
    }
    const IpoptOptionSpec* spec = FindIpoptOption(v.name);
    if (spec == nullptr || spec->type != v.type) {
      if (error) *error = "ipopt: extra option '" + v.name + "' is not in the table with that type";
      return false;
    }
    // Ipopt's own registry has the last word on a value (a spelling it does not take).
    if (!IpoptRegistryAccepts(v, error)) return false;
  }
  // The rules that tie options together: Ipopt's own answer, not a list of them.
  return IpoptAcceptsTogether(*this, error);
}

const OptionSchema& IpoptOptions::Schema() { return IpoptBinding().schema(); }

IpoptOptions IpoptOptions::Apply(const OptionMap& options, IpoptOptions base) {
  return IpoptBinding().ApplyValidated(options, std::move(base));
}

}  // namespace ocpb
