// Each feature kind's own options, held inside the localiser's options without
// the localiser knowing their types: a kind declares its options struct (its
// defaults in the member initialisers) and its blocks of the parameter file in
// its own folder, and reads them back with Get<ItsOptions>(), so that a new
// kind adds no member to a shared struct.
#pragma once

#include <any>
#include <deque>

namespace structloc::localisation_core {

class FeatureKindOptions {
 public:
  // The options of type P; their defaults when none were set (a reference to
  // those defaults then, which a later non-const Get does not change: take
  // the reference after the last change).
  template <class P>
  const P& Get() const {
    for (const auto& value : values_) {
      if (const P* found = std::any_cast<P>(&value)) return *found;
    }
    static const P kDefaults{};
    return kDefaults;
  }

  // The options of type P to change, starting from their defaults (the
  // reference stays valid while this object lives).
  template <class P>
  P& Get() {
    for (auto& value : values_) {
      if (P* found = std::any_cast<P>(&value)) return *found;
    }
    return std::any_cast<P&>(values_.emplace_back(P{}));
  }

 private:
  std::deque<std::any> values_;  // at most one per type; a deque keeps references valid
};

}  // namespace structloc::localisation_core
