// Binds an OptionSchema to the fields of an options struct: the schema's defaults are the
// struct's defaults, given values are written into the struct by type, and the struct's fields
// are checked by the same rules (one statement of every rule).
#pragma once

#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/option_schema.h"

namespace ocpb {

/// The option table of one options struct `Options` (default-constructible; its default
/// member values are the documented defaults). Typical use, in a solver's .cc file:
///
///   const OptionBinding<MyOptions>& Binding() {
///     static const OptionBinding<MyOptions> b = [] {
///       OptionBinding<MyOptions> t("my-solver");
///       t.Number("step", &MyOptions::step, "gradient step", OptionBounds::Above(0));
///       t.Integer("max_iterations", &MyOptions::max_iterations, "iteration limit",
///                 OptionBounds::AtLeast(0));
///       return t;
///     }();
///     return b;
///   }
///   MyOptions o = Binding().Apply(request.options, defaults);   // throws std::invalid_argument
///
/// Apply resolves every given value through the schema (unknown names refused with the list of
/// valid ones, values converted to their types and checked) and writes them into a copy of the
/// base; Check applies the same rules to a struct built in code (an Options::IsValid).
template <class Options>
class OptionBinding {
 public:
  explicit OptionBinding(std::string owner) : schema_(std::move(owner)) {}

  /// A double field.
  OptionBinding& Number(const std::string& name,
                        double Options::*field,
                        std::string doc,
                        OptionBounds bounds = OptionBounds::Any()) {
    return Bind(
        Spec(name, OptionType::kNumber, std::move(doc), Defaults().*field, bounds),
        [field](Options* o, const OptionValue& v) { o->*field = v.number(); },
        [field](const Options& o) { return OptionValue(o.*field); });
  }
  /// An int field (every integer option is within int's range: OptionSpec::Resolve).
  OptionBinding& Integer(const std::string& name,
                         int Options::*field,
                         std::string doc,
                         OptionBounds bounds = OptionBounds::Any()) {
    bounds.allow_infinite = false;
    return Bind(
        Spec(name, OptionType::kInteger, std::move(doc), Defaults().*field, bounds),
        [field](Options* o, const OptionValue& v) { o->*field = static_cast<int>(v.integer()); },
        [field](const Options& o) { return OptionValue(o.*field); });
  }
  OptionBinding& Bool(const std::string& name, bool Options::*field, std::string doc) {
    return Bind(
        Spec(name, OptionType::kBool, std::move(doc), Defaults().*field, {}),
        [field](Options* o, const OptionValue& v) { o->*field = v.boolean(); },
        [field](const Options& o) { return OptionValue(o.*field); });
  }
  /// A std::string field: any text when `choices` is empty, else one of them (an enum).
  OptionBinding& Text(const std::string& name,
                      std::string Options::*field,
                      std::string doc,
                      std::vector<std::string> choices = {}) {
    OptionSpec s = Spec(name,
                        choices.empty() ? OptionType::kText : OptionType::kEnum,
                        std::move(doc),
                        OptionValue(),
                        {});
    s.choices = std::move(choices);
    const std::string& d = Defaults().*field;
    if (!d.empty() || s.type == OptionType::kText) s.default_value = d;
    return Bind(
        std::move(s),
        [field](Options* o, const OptionValue& v) { o->*field = v.text(); },
        [field](const Options& o) { return OptionValue(o.*field); });
  }
  /// An enum-class field named by text: `names` lists every value with its name.
  template <class E>
  OptionBinding& Enum(const std::string& name,
                      E Options::*field,
                      std::vector<std::pair<std::string, E>> names,
                      std::string doc) {
    OptionSpec s = Spec(name, OptionType::kEnum, std::move(doc), OptionValue(), {});
    for (const auto& [text, value] : names) {
      s.choices.push_back(text);
      if (value == Defaults().*field) s.default_value = text;
    }
    return Bind(
        std::move(s),
        [field, names](Options* o, const OptionValue& v) {
          for (const auto& [text, value] : names) {
            if (text == v.text()) o->*field = value;
          }
        },
        [field, names](const Options& o) {
          for (const auto& [text, value] : names) {
            if (value == o.*field) return OptionValue(text);
          }
          return OptionValue("<unnamed>");  // fails Check: not one of the choices
        });
  }
  /// A std::optional<double> field: unset by default, meaning `unset_doc`.
  OptionBinding& OptionalNumber(const std::string& name,
                                std::optional<double> Options::*field,
                                std::string doc,
                                OptionBounds bounds,
                                std::string unset_doc) {
    OptionSpec s = Spec(name, OptionType::kNumber, std::move(doc), OptionValue(), bounds);
    if (const std::optional<double>& d = Defaults().*field) s.default_value = *d;
    s.unset_doc = std::move(unset_doc);
    return Bind(
        std::move(s),
        [field](Options* o, const OptionValue& v) { o->*field = v.number(); },
        [field](const Options& o) { return o.*field ? OptionValue(*(o.*field)) : OptionValue(); });
  }
  /// "PREFIX.NAME" options forwarded to another owner's schema, collected (resolved) in an
  /// OptionMap field.
  OptionBinding& Nested(const std::string& prefix,
                        OptionMap Options::*field,
                        const OptionSchema& nested,
                        std::string doc) {
    schema_.AddNested(prefix, nested, std::move(doc));
    nested_.push_back({prefix, field});
    return *this;
  }
  /// A double or int field of a struct nested in Options (or in a base of it): (o.*outer).*inner,
  /// for example the family's proximal schedule or a transcription's mesh refinement options.
  /// Its default is Defaults()'s (the struct this binding fills, presets included).
  template <class Base, class Outer, class T>
  OptionBinding& NestedMember(const std::string& name,
                              Outer Base::*outer,
                              T Outer::*inner,
                              std::string doc,
                              OptionBounds bounds = OptionBounds::Any()) {
    static_assert(std::is_base_of_v<Base, Options>, "outer must be a member of Options");
    static_assert(std::is_same_v<T, double> || std::is_same_v<T, int>,
                  "NestedMember binds double and int fields");
    constexpr bool kInt = std::is_same_v<T, int>;
    return Bind(
        Spec(name,
             kInt ? OptionType::kInteger : OptionType::kNumber,
             std::move(doc),
             OptionValue(Defaults().*outer.*inner),
             bounds),
        [outer, inner](Options* o, const OptionValue& v) {
          if constexpr (kInt) {
            o->*outer.*inner = static_cast<int>(v.integer());
          } else {
            o->*outer.*inner = v.number();
          }
        },
        [outer, inner](const Options& o) { return OptionValue(o.*outer.*inner); });
  }
  /// Any other spec, with its own setter (for example a field of another type).
  OptionBinding& Custom(OptionSpec spec,
                        std::function<void(Options*, const OptionValue&)> set,
                        std::function<OptionValue(const Options&)> get) {
    return Bind(std::move(spec), std::move(set), std::move(get));
  }

  const OptionSchema& schema() const { return schema_; }

  /// `base` with every entry of `given` applied. Throws std::invalid_argument (unknown name,
  /// wrong type, broken rule) before changing anything.
  Options Apply(const OptionMap& given, Options base) const {
    const OptionMap resolved = schema_.Resolve(given);
    for (const auto& [name, value] : resolved) {
      if (const NestedField* n = FindNested(name)) {
        (base.*(n->field)).Set(name.substr(n->prefix.size() + 1), value);
        continue;
      }
      if (value.empty()) continue;  // unset: the base's value stays
      for (const Entry& e : entries_) {
        if (e.name == name) e.set(&base, value);
      }
    }
    return base;
  }

  /// Apply, then the struct's own cross-field rules: `Options::IsValid(std::string*)` when it has
  /// one. Throws std::invalid_argument with the first broken rule.
  Options ApplyValidated(const OptionMap& given, Options base) const {
    Options o = Apply(given, std::move(base));
    if constexpr (requires(const Options& x, std::string* e) { x.IsValid(e); }) {
      std::string error;
      if (!o.IsValid(&error)) throw std::invalid_argument(error);
    }
    return o;
  }

  /// Every bound field of `o` checked against its rule; false with "NAME: must be ..." in
  /// *error (may be null) for the first that breaks it. Nested maps are checked by name.
  bool Check(const Options& o, std::string* error) const {
    try {
      for (const Entry& e : entries_) schema_.ResolveOne(e.name, e.get(o));
      for (const NestedField& n : nested_) {
        for (const auto& [name, value] : o.*(n.field))
          schema_.ResolveOne(n.prefix + "." + name, value);
      }
    } catch (const std::invalid_argument& e) {
      if (error) *error = e.what();
      return false;
    }
    return true;
  }

  /// The value of every bound option in `o` (unset optionals left out): what a record lists as
  /// the options a solve really used.
  OptionMap Values(const Options& o) const {
    OptionMap out;
    for (const Entry& e : entries_) {
      OptionValue v = e.get(o);
      if (!v.empty()) out.Set(e.name, std::move(v));
    }
    for (const NestedField& n : nested_) {
      for (const auto& [name, value] : o.*(n.field)) out.Set(n.prefix + "." + name, value);
    }
    return out;
  }

 private:
  struct Entry {
    std::string name;
    std::function<void(Options*, const OptionValue&)> set;
    std::function<OptionValue(const Options&)> get;
  };
  struct NestedField {
    std::string prefix;
    OptionMap Options::*field;
  };

  static const Options& Defaults() {
    static const Options defaults{};
    return defaults;
  }
  static OptionSpec Spec(const std::string& name,
                         OptionType type,
                         std::string doc,
                         OptionValue default_value,
                         OptionBounds bounds) {
    OptionSpec s;
    s.name = name;
    s.type = type;
    s.doc = std::move(doc);
    s.default_value = std::move(default_value);
    s.bounds = bounds;
    return s;
  }
  OptionBinding& Bind(OptionSpec spec,
                      std::function<void(Options*, const OptionValue&)> set,
                      std::function<OptionValue(const Options&)> get) {
    const std::string name = spec.name;
    schema_.Add(std::move(spec));
    entries_.push_back({name, std::move(set), std::move(get)});
    return *this;
  }
  const NestedField* FindNested(const std::string& name) const {
    for (const NestedField& n : nested_) {
      if (name.size() > n.prefix.size() + 1 && name.compare(0, n.prefix.size(), n.prefix) == 0 &&
          name[n.prefix.size()] == '.') {
        return &n;
      }
    }
    return nullptr;
  }

  OptionSchema schema_;
  std::vector<Entry> entries_;
  std::vector<NestedField> nested_;
};

}  // namespace ocpb
