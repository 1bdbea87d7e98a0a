#include "core/option_schema.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace ocpb {
namespace {

std::string Num(double v) { return OptionValue(v).ToText(); }

// What a user wrote, for "(got ...)": text in quotes, typed values as their text.
std::string Got(const OptionValue& v) {
  if (v.kind() == OptionValue::Kind::kText) {
    std::string shown;
    for (char c : v.text()) shown += (c == '\n' || c == '\r') ? ' ' : c;  // stay one line
    return "'" + shown + "'";
  }
  return v.ToText();
}

std::string Join(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& s : items) out += (out.empty() ? "" : ", ") + s;
  return out;
}

[[noreturn]] void Refuse(const OptionSpec& spec, const OptionValue& given) {
  throw std::invalid_argument("option '" + spec.name + "': must be " + spec.Rule() + " (got " +
                              Got(given) + ")");
}

// A number for a kNumber or kVector component: typed numbers and integers as they are, text by
// the grammar; nullopt when `given` is no number at all.
std::optional<double> AsNumber(const OptionValue& given) {
  switch (given.kind()) {
    case OptionValue::Kind::kNumber:
      return given.number();
    case OptionValue::Kind::kInteger:
      return static_cast<double>(given.integer());
    case OptionValue::Kind::kText:
      return ParseNumberText(given.text());
    default:
      return std::nullopt;
  }
}

std::vector<std::string> SplitCommas(const std::string& text) {
  std::vector<std::string> items;
  size_t begin = 0;
  while (true) {
    const size_t comma = text.find(',', begin);
    items.push_back(
        text.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin));
    if (comma == std::string::npos) break;
    begin = comma + 1;
  }
  return items;
}

}  // namespace

const char* ToString(OptionType type) {
  switch (type) {
    case OptionType::kNumber:
      return "number";
    case OptionType::kInteger:
      return "integer";
    case OptionType::kBool:
      return "bool";
    case OptionType::kEnum:
      return "enum";
    case OptionType::kText:
      return "text";
    case OptionType::kVector:
      return "vector";
  }
  return "?";
}

bool OptionBounds::Contains(double v) const {
  if (std::isnan(v)) return false;
  if (std::isinf(v) && !allow_infinite) return false;
  const bool above_min = min_exclusive ? v > min : v >= min;
  const bool below_max = max_exclusive ? v < max : v <= max;
  return above_min && below_max;
}

std::string OptionBounds::Describe() const {
  const bool has_min = std::isfinite(min), has_max = std::isfinite(max);
  std::string text;
  if (has_min && has_max) {
    text = std::string("in ") + (min_exclusive ? "(" : "[") + Num(min) + ", " + Num(max) +
           (max_exclusive ? ")" : "]");
  } else if (has_min) {
    text = std::string(min_exclusive ? "> " : ">= ") + Num(min);
  } else if (has_max) {
    text = std::string(max_exclusive ? "< " : "<= ") + Num(max);
  }
  if (allow_infinite) {
    const bool pos = !has_max, neg = !has_min;
    const std::string inf = pos && neg ? "+-inf" : pos ? "inf" : neg ? "-inf" : "";
    if (!inf.empty()) text += (text.empty() ? "finite or " : ", or ") + inf;
  }
  return text;
}

std::string OptionSpec::Rule() const {
  const std::string range = bounds.Describe();
  switch (type) {
    case OptionType::kNumber:
      return range.empty() ? "a finite number" : "a number " + range;
    case OptionType::kInteger:
      return range.empty() ? "an integer" : "an integer " + range;
    case OptionType::kBool:
      return "true or false (1 or 0)";
    case OptionType::kEnum:
      return "one of: " + Join(choices);
    case OptionType::kText:
      return "a text";
    case OptionType::kVector: {
      const std::string count =
          size > 0 ? std::to_string(size) + (size == 1 ? " number" : " numbers") : "numbers";
      return "a list of " + count + (range.empty() ? "" : " " + range) + " (a,b,...)";
    }
  }
  return "valid";
}

std::string OptionSpec::DefaultText() const {
  if (default_value.empty()) return "unset" + (unset_doc.empty() ? "" : " (" + unset_doc + ")");
  return default_value.ToText();
}

OptionValue OptionSpec::Resolve(const OptionValue& given) const {
  if (given.empty()) return given;
  using Kind = OptionValue::Kind;
  switch (type) {
    case OptionType::kNumber: {
      const std::optional<double> v = AsNumber(given);
      if (!v || !bounds.Contains(*v)) Refuse(*this, given);
      return *v;
    }
    case OptionType::kInteger: {
      // Every integer option is an int (counts, limits, levels): beyond its range is refused.
      constexpr double kIntMin = std::numeric_limits<int>::min();
      constexpr double kIntMax = std::numeric_limits<int>::max();
      const std::optional<double> v =
          given.kind() == Kind::kInteger
              ? std::optional<double>(static_cast<double>(given.integer()))
              : AsNumber(given);
      if (!v || !std::isfinite(*v) || *v != std::floor(*v) || !bounds.Contains(*v)) {
        Refuse(*this, given);
      }
      if (*v < kIntMin || *v > kIntMax) {  // within the rule's bounds, beyond an int's
        throw std::invalid_argument("option '" + name + "': must be " + Rule() +
                                    " and within an int, [-2147483648, 2147483647] (got " +
                                    Got(given) + ")");
      }
      return static_cast<long long>(*v);
    }
    case OptionType::kBool:
      if (given.kind() == Kind::kBool) return given;
      if (given.kind() == Kind::kInteger && (given.integer() == 0 || given.integer() == 1)) {
        return given.integer() == 1;
      }
      if (given.kind() == Kind::kText) {
        const std::string& t = given.text();
        if (t == "true" || t == "1") return true;
        if (t == "false" || t == "0") return false;
      }
      Refuse(*this, given);
    case OptionType::kEnum:
      if (given.kind() == Kind::kText &&
          std::find(choices.begin(), choices.end(), given.text()) != choices.end()) {
        return given;
      }
      Refuse(*this, given);
    case OptionType::kText:
      if (given.kind() != Kind::kText) Refuse(*this, given);
      return given;
    case OptionType::kVector: {
      std::vector<double> values;
      if (given.kind() == Kind::kVector) {
        values = given.vector();
      } else if (given.kind() == Kind::kText) {
        for (const std::string& item : SplitCommas(given.text())) {
          const std::optional<double> v = ParseNumberText(item);
          if (!v) Refuse(*this, given);
          values.push_back(*v);
        }
      } else if (const std::optional<double> v = AsNumber(given)) {
        values.push_back(*v);
      } else {
        Refuse(*this, given);
      }
      if (values.empty() || (size > 0 && static_cast<int>(values.size()) != size)) {
        Refuse(*this, given);
      }
      for (double v : values) {
        if (!bounds.Contains(v)) Refuse(*this, given);
      }
      return values;
    }
  }
  Refuse(*this, given);
}

void OptionSchema::Add(OptionSpec spec) {
  const std::string who = owner_.empty() ? "option schema" : owner_;
  if (spec.name.empty()) throw std::logic_error(who + ": an option without a name");
  if (spec.name.find('.') != std::string::npos) {
    throw std::logic_error(who + ": option '" + spec.name +
                           "': '.' is reserved for nested options");
  }
  for (const OptionSpec& s : specs_) {
    if (s.name == spec.name) throw std::logic_error(who + ": duplicate option '" + spec.name + "'");
  }
  if (spec.type == OptionType::kEnum && spec.choices.empty()) {
    throw std::logic_error(who + ": enum option '" + spec.name + "' without choices");
  }
  if (!spec.default_value.empty()) {
    try {
      spec.default_value = spec.Resolve(spec.default_value);
    } catch (const std::invalid_argument& e) {
      throw std::logic_error(who + ": the default of " + e.what());
    }
  }
  specs_.push_back(std::move(spec));
}

void OptionSchema::AddNested(const std::string& prefix,
                             const OptionSchema& nested,
                             std::string doc) {
  if (prefix.empty() || prefix.find('.') != std::string::npos) {
    throw std::logic_error(owner_ + ": a nested prefix must be a non-empty name without '.'");
  }
  nested_.push_back({prefix, nested.specs(), nested.owner(), std::move(doc)});
}

const OptionSpec* OptionSchema::Find(const std::string& name) const {
  for (const OptionSpec& s : specs_) {
    if (s.name == name) return &s;
  }
  for (const Nested& n : nested_) {
    if (name.size() > n.prefix.size() + 1 && name.compare(0, n.prefix.size(), n.prefix) == 0 &&
        name[n.prefix.size()] == '.') {
      const std::string inner = name.substr(n.prefix.size() + 1);
      for (const OptionSpec& s : n.specs) {
        if (s.name == inner) return &s;
      }
    }
  }
  return nullptr;
}

std::string OptionSchema::Names() const {
  std::vector<std::string> names;
  for (const OptionSpec& s : specs_) names.push_back(s.name);
  for (const Nested& n : nested_) names.push_back(n.prefix + ".<" + n.owner + " option>");
  return names.empty() ? "none" : Join(names);
}

OptionValue OptionSchema::ResolveOne(const std::string& name, const OptionValue& value) const {
  const OptionSpec* spec = Find(name);
  if (spec == nullptr) {
    throw std::invalid_argument(owner_ + ": unknown option '" + name + "' (valid: " + Names() +
                                ")");
  }
  try {
    return spec->Resolve(value);
  } catch (const std::invalid_argument& e) {
    // Name the option as given (with its prefix), and whose it is.
    const std::string what = e.what();
    const std::string inner = "option '" + spec->name + "'";
    const std::string rest =
        what.compare(0, inner.size(), inner) == 0 ? what.substr(inner.size()) : ": " + what;
    throw std::invalid_argument(owner_ + " option '" + name + "'" + rest);
  }
}

OptionMap OptionSchema::Resolve(const OptionMap& given) const {
  OptionMap out;
  for (const auto& [name, value] : given) out.Set(name, ResolveOne(name, value));
  return out;
}

std::string OptionSchema::Describe() const {
  std::ostringstream os;
  auto line = [&os](const std::string& name, const OptionSpec& s) {
    os << "  " << name << " (" << ToString(s.type) << ", default " << s.DefaultText()
       << "): " << s.Rule() << ". " << s.doc << "\n";
  };
  for (const OptionSpec& s : specs_) line(s.name, s);
  for (const Nested& n : nested_) {
    os << "  " << n.prefix << ".<option>: " << n.doc << "; the " << n.owner << " options:\n";
    for (const OptionSpec& s : n.specs) line(n.prefix + "." + s.name, s);
  }
  if (specs_.empty() && nested_.empty()) os << "  (no options)\n";
  return os.str();
}

}  // namespace ocpb
