// Options declared once. Each option of an options struct is declared in one
// place with its XML key (unit in the name), where it lives in the struct, its
// valid range, unit and description; the struct's own member initialiser is the
// default. Loading a section from XML (strict: unknown or missing keys are
// errors naming file:line), validation (naming section and key) and a printed
// listing all derive from that declaration, so key, default and range cannot
// drift apart. Generic over the options struct and DDS-free, for parameter,
// scenario and robot files alike. A file whose root names a base
// (base="defaults", or another file of the same kind beside it) states only
// what differs from it; unknown keys stay errors.
#pragma once

#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <ostream>
#include <set>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "structloc/config/strict_xml.hpp"

namespace structloc::config {

// The valid values of a number: from min to max, either end open or unbounded;
// with `magnitude`, the bounds apply to the absolute value (either sign).
// Values must also be finite.
struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_open = false;
  bool max_open = false;
  bool magnitude = false;

  static Range Any() { return {}; }
  static Range Positive() { return {0.0, Range{}.max, true, false, false}; }
  static Range NonNegative() { return {0.0, Range{}.max, false, false, false}; }
  static Range AtLeast(double min) { return {min, Range{}.max, false, false, false}; }
  static Range Closed(double min, double max) { return {min, max, false, false, false}; }
  static Range Open(double min, double max) { return {min, max, true, true, false}; }
  static Range LeftOpen(double min, double max) { return {min, max, true, false, false}; }
  // |value| in [min, max], e.g. a non-zero scale factor of either sign.
  static Range Magnitude(double min, double max) { return {min, max, false, false, true}; }

  bool Contains(double value) const;
  // "> 0", ">= 1", "in (0, 1.570796327)", "in [1, 60]", "finite",
  // "magnitude in [1e-09, 1]".
  std::string Describe() const;
};

// Formats a value for listings and messages (shortest of 10 significant digits).
std::string FormatNumber(double value);

// How an out-of-range value is reported after "section: ", from the key, the
// value as text, the valid values (Range::Describe) and the unit (may be empty).
// The default reads "key must be VALID, not VALUE".
using OutOfRangeWording =
    std::function<std::string(const std::string& key, const std::string& value,
                              const std::string& valid, const std::string& unit)>;

// The options of one XML section (one element whose attributes are the keys)
// of the options struct S.
template <class S>
class OptionTable {
 public:
  OptionTable(std::string section, std::string description)
      : section_(std::move(section)), description_(std::move(description)) {}

  // Words out-of-range values of this table differently (see OutOfRangeWording);
  // integers read from a file are then checked with it too.
  OptionTable& Wording(OutOfRangeWording wording) {
    wording_ = std::move(wording);
    return *this;
  }

  // A number (double or integer type) stored in s.*member.
  template <class T>
  OptionTable& Number(const char* key, T S::*member, Range range, const char* unit,
                      const char* description) {
    return AddNumber<T>(
        key, range, unit, description, [member](auto& s) -> auto& { return s.*member; });
  }
  // A number stored in (s.*outer).*member, e.g. (&Options::walls, &WallOptions::gate_m).
  template <class M, class T>
  OptionTable& Number(const char* key, M S::*outer, T M::*member, Range range, const char* unit,
                      const char* description) {
    return AddNumber<T>(
        key, range, unit, description,
        [ outer, member ](auto& s) -> auto& { return (s.*outer).*member; });
  }
  // "true" or "false".
  OptionTable& Flag(const char* key, bool S::*member, const char* description) {
    return AddFlag(
        key, description, [member](auto& s) -> auto& { return s.*member; });
  }
  template <class M>
  OptionTable& Flag(const char* key, M S::*outer, bool M::*member, const char* description) {
    return AddFlag(
        key, description, [ outer, member ](auto& s) -> auto& { return (s.*outer).*member; });
  }
  // One of the named values of an enumeration.
  template <class E>
  OptionTable& Choice(const char* key, E S::*member, std::vector<std::pair<std::string, E>> names,
                      const char* description) {
    return AddChoice<E>(
        key, std::move(names), description, [member](auto& s) -> auto& { return s.*member; });
  }
  template <class M, class E>
  OptionTable& Choice(const char* key, M S::*outer, E M::*member,
                      std::vector<std::pair<std::string, E>> names, const char* description) {
    return AddChoice<E>(
        key, std::move(names), description,
        [ outer, member ](auto& s) -> auto& { return (s.*outer).*member; });
  }

  // Free text, e.g. a name.
  OptionTable& Text(const char* key, std::string S::*member, const char* description) {
    Entry e{key, "", "text", description, {}, {}, {}, false};
    const std::string name = key;
    e.load = [name, member](const OptionTable&, AttributeReader& reader, S& s) {
      s.*member = reader.String(name.c_str());
    };
    e.check = [](const OptionTable&, const S&) { return std::string(); };
    e.show = [member](const S& s) { return s.*member; };
    entries_.push_back(std::move(e));
    return *this;
  }

  // The table `part_table`, declared on a part P of S, as a table of S:
  // `part(s)` finds the part in an S, const or not (e.g. a feature kind's own
  // options inside the localiser's). Keys, ranges, wording and defaults are
  // those of `part_table`.
  template <class P, class Part>
  static OptionTable Of(const OptionTable<P>& part_table, Part part) {
    OptionTable out(part_table.section_, part_table.description_);
    const auto inner = std::make_shared<const OptionTable<P>>(part_table);
    for (size_t i = 0; i < inner->entries_.size(); ++i) {
      const auto& e = inner->entries_[i];
      Entry x{e.key, e.unit, e.valid, e.description, {}, {}, {}, e.optional};
      x.load = [inner, i, part](const OptionTable&, AttributeReader& reader, S& s) {
        inner->entries_[i].load(*inner, reader, part(s));
      };
      x.check = [inner, i, part](const OptionTable&, const S& s) {
        return inner->entries_[i].check(*inner, part(s));
      };
      x.show = [inner, i, part](const S& s) { return inner->entries_[i].show(part(s)); };
      out.entries_.push_back(std::move(x));
    }
    return out;
  }

  // Makes the key declared last optional: when a file leaves it out, the
  // member keeps the value it had (the default). Listed as "[optional]".
  OptionTable& Optional() {
    if (!entries_.empty()) entries_.back().optional = true;
    return *this;
  }

  const std::string& Section() const { return section_; }
  bool HasOptionalKeys() const {
    for (const auto& e : entries_) {
      if (e.optional) return true;
    }
    return false;
  }

  // Every key with the value of `options` as text (numbers with 10 significant
  // digits, choices by name, text as it is: escape it for XML), in declaration
  // order: for writing a file.
  std::vector<std::pair<std::string, std::string>> Values(const S& options) const {
    std::vector<std::pair<std::string, std::string>> values;
    for (const auto& e : entries_) values.emplace_back(e.key, e.show(options));
    return values;
  }

  // Reads every key of `element` into `out`; throws ConfigError naming
  // file:line for a missing, unknown, malformed or out-of-range value. With
  // `only_given`, a key left out keeps the value `out` has (a file with a base).
  void Load(const XmlFile& file, const tinyxml2::XMLElement& element, S& out,
            bool only_given = false) const {
    AttributeReader reader(file, element);
    for (const auto& e : entries_) {
      if ((!e.optional && !only_given) || reader.Has(e.key.c_str())) e.load(*this, reader, out);
    }
    reader.Finish();
    const std::string problem = FirstProblem(out);
    if (!problem.empty()) file.Fail(element, problem);
  }

  // Throws std::invalid_argument "section: key must be ..., not VALUE".
  void Validate(const S& options) const {
    const std::string problem = FirstProblem(options);
    if (!problem.empty()) throw std::invalid_argument(problem);
  }

  // One line per key: key, default (from `defaults`), unit, valid values, description.
  void Print(std::ostream& out, const S& defaults) const {
    out << "<" << section_ << ">  " << description_ << "\n";
    for (const auto& e : entries_) {
      const std::string shown = e.show(defaults);
      out << "  " << Pad(e.key, 28) << " " << Pad(shown.empty() ? "\"\"" : shown, 14) << " "
          << Pad(e.unit.empty() ? "-" : e.unit, 5) << " " << Pad(e.valid, 26) << " "
          << (e.optional ? "[optional] " : "") << e.description << "\n";
    }
  }

 private:
  // The functions take the table (not captured, so that tables copy safely)
  // for its wording.
  struct Entry {
    std::string key, unit, valid, description;
    std::function<void(const OptionTable&, AttributeReader&, S&)> load;
    std::function<std::string(const OptionTable&, const S&)> check;  // empty when valid
    std::function<std::string(const S&)> show;
    bool optional = false;
  };

  std::string OutOfRange(const std::string& key, const std::string& value, const std::string& valid,
                         const std::string& unit) const {
    if (wording_) return wording_(key, value, valid, unit);
    return key + " must be " + valid + ", not " + value;
  }

  static std::string Pad(const std::string& text, size_t width) {
    return text.size() >= width ? text : text + std::string(width - text.size(), ' ');
  }

  std::string FirstProblem(const S& options) const {
    for (const auto& e : entries_) {
      std::string why = e.check(*this, options);
      if (!why.empty()) return section_ + ": " + why;
    }
    return {};
  }

  template <class T, class Get>
  OptionTable& AddNumber(const char* key, Range range, const char* unit, const char* description,
                         Get get) {
    static_assert(std::is_arithmetic_v<T> && !std::is_same_v<T, bool>, "use Flag for bool");
    const bool any_integer =
        std::is_integral_v<T> && !std::isfinite(range.min) && !std::isfinite(range.max);
    Entry e{key, unit, any_integer ? "integer" : range.Describe(), description, {}, {}, {}, false};
    const std::string name = key, unit_name = unit;
    e.load = [name, unit_name, range, get](const OptionTable& table, AttributeReader& reader,
                                           S& s) {
      if constexpr (std::is_integral_v<T>) {
        // Bounds within T's own range, so that a value is never truncated (a
        // magnitude range's lower bound is checked after reading, by `check`).
        constexpr T kMin = std::numeric_limits<T>::min(), kMax = std::numeric_limits<T>::max();
        const double min = range.magnitude ? -range.max : range.min;
        const T lo = min <= static_cast<double>(kMin) ? kMin : static_cast<T>(std::ceil(min));
        const T hi =
            range.max >= static_cast<double>(kMax) ? kMax : static_cast<T>(std::floor(range.max));
        if (!table.wording_) {
          get(s) = reader.IntegerIn<T>(name.c_str(), lo, hi);
          return;
        }
        // Checked as read, before narrowing to T (4294967328 must not become 32).
        const long long value = reader.Integer(name.c_str());
        // Compared as doubles: an unsigned 64-bit bound does not fit a long long.
        if (!range.Contains(static_cast<double>(value)) ||
            static_cast<double>(value) < static_cast<double>(lo) ||
            static_cast<double>(value) > static_cast<double>(hi)) {
          reader.Fail(table.section_ + ": " +
                      table.OutOfRange(name, std::to_string(value), range.Describe(), unit_name));
        }
        get(s) = static_cast<T>(value);
      } else {
        static_cast<void>(range);  // checked after reading, by `check`
        get(s) = static_cast<T>(reader.Double(name.c_str()));
      }
    };
    e.check = [name, unit_name, range, get](const OptionTable& table, const S& s) -> std::string {
      const double value = static_cast<double>(get(s));
      if (range.Contains(value)) return {};
      return table.OutOfRange(name, FormatNumber(value), range.Describe(), unit_name);
    };
    e.show = [get](const S& s) { return FormatNumber(static_cast<double>(get(s))); };
    entries_.push_back(std::move(e));
    return *this;
  }

  template <class Get>
  OptionTable& AddFlag(const char* key, const char* description, Get get) {
    Entry e{key, "", "true or false", description, {}, {}, {}, false};
    const std::string name = key;
    e.load = [name, get](const OptionTable&, AttributeReader& reader, S& s) {
      get(s) = reader.Bool(name.c_str());
    };
    e.check = [](const OptionTable&, const S&) { return std::string(); };
    e.show = [get](const S& s) { return std::string(get(s) ? "true" : "false"); };
    entries_.push_back(std::move(e));
    return *this;
  }

  template <class E, class Get>
  OptionTable& AddChoice(const char* key, std::vector<std::pair<std::string, E>> names,
                         const char* description, Get get) {
    std::string valid;  // "a, b or c"
    for (size_t i = 0; i < names.size(); ++i) {
      valid += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i].first;
    }
    Entry e{key, "", valid, description, {}, {}, {}, false};
    const std::string name = key;
    e.load = [name, names, valid, get](const OptionTable&, AttributeReader& reader, S& s) {
      const std::string value = reader.String(name.c_str());
      for (const auto& n : names) {
        if (n.first == value) {
          get(s) = n.second;
          return;
        }
      }
      reader.Fail(name + " must be " + valid + ", not '" + value + "'");
    };
    e.check = [name, names, valid, get](const OptionTable&, const S& s) -> std::string {
      for (const auto& n : names) {
        if (n.second == get(s)) return {};
      }
      return name + " must be " + valid;
    };
    e.show = [names, get](const S& s) {
      for (const auto& n : names) {
        if (n.second == get(s)) return n.first;
      }
      return std::string("?");
    };
    entries_.push_back(std::move(e));
    return *this;
  }

  template <class>
  friend class OptionTable;  // Of() reads a part's table

  std::string section_, description_;
  std::vector<Entry> entries_;
  OutOfRangeWording wording_;
};

// A file whose root element holds one element per OptionTable, each exactly
// once, and nothing else. Its root may name a base: base="defaults" (the
// options struct's own defaults, as `structloc params` lists them) or
// base="OTHER.xml" (a file of the same kind, its path relative to this
// file's folder, itself complete or based in turn); the file then states only
// the sections and keys that differ from its base.
template <class S>
class OptionFile {
 public:
  // `other_sections`: sections of the same file that another options struct
  // reads (allowed here, not loaded).
  OptionFile(std::string root, std::vector<OptionTable<S>> sections,
             std::set<std::string> other_sections = {})
      : root_(std::move(root)),
        sections_(std::move(sections)),
        other_sections_(std::move(other_sections)) {}

  const std::string& RootName() const { return root_; }
  const std::vector<OptionTable<S>>& Sections() const { return sections_; }

  // Bases based on bases, at most this deep (a file based on itself fails).
  static constexpr int kMaxBaseDepth = 8;

  // Loads every section into a copy of `defaults` (or of what the file's base
  // gives); throws ConfigError naming file:line for any problem.
  S Load(const XmlFile& file, S defaults = S{}) const {
    return LoadBased(file, std::move(defaults), 0);
  }

  void Validate(const S& options) const {
    for (const auto& t : sections_) t.Validate(options);
  }

  // Loads the file at `path` and checks the options as a whole (S::Validate,
  // which throws std::invalid_argument for values that contradict each
  // other): ConfigError naming the file for either.
  S LoadValidated(const std::string& path) const {
    const auto file = XmlFile::Load(path);
    S options = Load(file);
    try {
      options.Validate();
    } catch (const std::invalid_argument& e) {
      file.Fail(file.Root(), e.what());
    }
    return options;
  }

  // The file at `path` whole: its root with every section and key as it
  // loads them (its own or its base's).
  void WriteExpanded(const std::string& path, std::ostream& out) const {
    const S options = LoadValidated(path);
    out << "<" << root_ << ">\n";
    WriteSections(out, options);
    out << "</" << root_ << ">\n";
  }

  void Print(std::ostream& out, const S& defaults) const {
    bool optional = false;
    for (const auto& t : sections_) optional = optional || t.HasOptionalKeys();
    out << "<" << root_ << ">: every key below is required"
        << (optional ? " unless marked [optional]" : "")
        << " (a file whose root says base=\"defaults\" or base=\"OTHER.xml\" states only what "
           "differs from that); columns: key, default, unit, valid values, meaning\n";
    for (const auto& t : sections_) t.Print(out, defaults);
  }

  // Every section of `options` as XML elements with every key (values as
  // Values gives them; text is not escaped), one per line.
  void WriteSections(std::ostream& out, const S& options) const {
    for (const auto& t : sections_) {
      out << "  <" << t.Section();
      for (const auto& [key, value] : t.Values(options))
        out << " " << key << "=\"" << value << "\"";
      out << "/>\n";
    }
  }

 private:
  S LoadBased(const XmlFile& file, S defaults, int depth) const {
    const auto& root = file.Root(root_);
    std::optional<std::string> base;
    {
      AttributeReader reader(file, root);
      if (reader.Has("base")) base = reader.String("base");
      reader.Finish();  // no other attribute
    }
    if (base && *base != "defaults") {
      if (depth >= kMaxBaseDepth) {
        file.Fail(root, "base=\"" + *base + "\": more than " + std::to_string(kMaxBaseDepth) +
                            " files based on one another (is a file its own base?)");
      }
      const auto beside = std::filesystem::path(file.Path()).parent_path() / *base;
      const XmlFile base_file = [&] {
        try {
          return XmlFile::Load(beside.string());
        } catch (const ConfigError& e) {
          file.Fail(root, "base=\"" + *base + "\": " + e.what());
        }
      }();
      defaults = LoadBased(base_file, std::move(defaults), depth + 1);
    }
    std::set<std::string> names = other_sections_;
    for (const auto& t : sections_) names.insert(t.Section());
    RequireChildNames(file, root, names);
    for (const auto& t : sections_) {
      const auto* element = root.FirstChildElement(t.Section().c_str());
      if (element == nullptr) {
        if (base) continue;  // all of it as the base has it
        file.Fail(root, "missing section <" + t.Section() + ">");
      }
      if (const auto* second = element->NextSiblingElement(t.Section().c_str())) {
        file.Fail(*second, "a second <" + t.Section() + "> section; write each section once");
      }
      t.Load(file, *element, defaults, base.has_value());
    }
    return defaults;
  }

  std::string root_;
  std::vector<OptionTable<S>> sections_;
  std::set<std::string> other_sections_;
};

}  // namespace structloc::config
