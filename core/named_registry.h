// A list of named entries (problems, solvers, transcriptions): the built-in ones, then those a
// user registers, looked up by name with errors that list the valid names.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace ocpb {

/// `Info` has a `std::string name`. The built-in entries are made on first use. Registration
/// is for program start-up: it is not synchronized with concurrent lookups, and it invalidates
/// references previously returned by All() and Find().
template <class Info>
class NamedRegistry {
 public:
  /// `what` names an entry in messages ("solver"); `builtins` makes the built-in entries.
  NamedRegistry(std::string what, std::function<std::vector<Info>()> builtins)
      : what_(std::move(what)), builtins_(std::move(builtins)) {}

  const std::vector<Info>& All() {
    if (!built_) {
      entries_ = builtins_();
      built_ = true;
    }
    return entries_;
  }

  /// The entry called `name`; std::invalid_argument "unknown WHAT 'NAME' (valid: a, b)".
  const Info& Find(const std::string& name) {
    for (const Info& i : All()) {
      if (i.name == name) return i;
    }
    throw std::invalid_argument("unknown " + what_ + " '" + name + "' (valid: " + Names() + ")");
  }

  /// "a, b, c" (or "none").
  std::string Names() {
    std::string names;
    for (const Info& i : All()) names += (names.empty() ? "" : ", ") + i.name;
    return names.empty() ? "none" : names;
  }

  /// Appends `info` after the existing entries. `check` runs first and throws
  /// std::invalid_argument for an incomplete entry; an empty or taken name is refused here,
  /// with messages that start with `caller` ("RegisterSolver").
  void Add(const std::string& caller,
           Info info,
           const std::function<void(const Info&)>& check = nullptr) {
    if (info.name.empty()) throw std::invalid_argument(caller + ": the name must not be empty");
    if (check) check(info);
    for (const Info& i : All()) {
      if (i.name == info.name) {
        throw std::invalid_argument(caller + ": a " + what_ + " named '" + info.name +
                                    "' exists already");
      }
    }
    entries_.push_back(std::move(info));
  }

 private:
  std::string what_;
  std::function<std::vector<Info>()> builtins_;
  std::vector<Info> entries_;
  bool built_ = false;
};

}  // namespace ocpb
