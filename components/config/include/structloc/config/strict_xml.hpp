// Strict reading of our XML files (maps, scenarios, parameters, launch): every
// problem names the file and line, unknown attributes and elements are errors,
// missing or non-numeric values are errors. DDS-free.
#pragma once

#include <tinyxml2.h>

#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace structloc::config {

// A configuration problem a user can act on: "FILE:LINE: what is wrong".
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A parsed XML file that remembers its path for error messages.
class XmlFile {
 public:
  // The largest XML file read: a map of 250000 walls (the largest a world
  // may have) takes about 25 MB.
  static constexpr size_t kDefaultMaxBytes = 64u << 20;

  // Throws ConfigError when the file is missing, a folder, unreadable, larger
  // than `max_bytes`, not well-formed, has a document type declaration
  // (<!DOCTYPE ...>: no entity is ever defined or expanded, no external file
  // read), or has more than one root element.
  static XmlFile Load(const std::string& path, size_t max_bytes = kDefaultMaxBytes);

  const tinyxml2::XMLElement& Root() const;
  // Checks the root element's name.
  const tinyxml2::XMLElement& Root(const std::string& expected_name) const;
  const std::string& Path() const { return path_; }

  [[noreturn]] void Fail(const tinyxml2::XMLElement& where, const std::string& what) const;

 private:
  XmlFile() = default;
  std::string path_;
  std::unique_ptr<tinyxml2::XMLDocument> doc_;
};

// Reads the attributes of one element and checks, in Finish(), that no
// attribute was left unread (an unknown key is an error, never ignored).
class AttributeReader {
 public:
  AttributeReader(const XmlFile& file, const tinyxml2::XMLElement& element);

  double Double(const char* name);
  double PositiveDouble(const char* name);
  double NonNegativeDouble(const char* name);
  std::optional<double> OptionalDouble(const char* name);
  // A finite number in [min, max]; the message names the bound.
  double DoubleIn(const char* name, double min, double max);
  long long Integer(const char* name);
  std::optional<long long> OptionalInteger(const char* name);
  // An integer in [min, max] (by default the whole range of T), returned as T:
  // never truncated or wrapped into a narrower type.
  template <class T>
  T IntegerIn(const char* name, T min = std::numeric_limits<T>::min(),
              T max = std::numeric_limits<T>::max()) {
    return static_cast<T>(CheckedInteger(name, Integer(name), Clamp(min), Clamp(max)));
  }
  template <class T>
  std::optional<T> OptionalIntegerIn(const char* name, T min = std::numeric_limits<T>::min(),
                                     T max = std::numeric_limits<T>::max()) {
    const auto value = OptionalInteger(name);
    if (!value) return std::nullopt;
    return static_cast<T>(CheckedInteger(name, *value, Clamp(min), Clamp(max)));
  }
  bool Bool(const char* name);
  std::string String(const char* name);
  std::optional<std::string> OptionalString(const char* name);
  bool Has(const char* name) const;

  // Throws ConfigError naming every attribute that was not read.
  void Finish() const;
  [[noreturn]] void Fail(const std::string& what) const;

 private:
  const char* Raw(const char* name);
  long long CheckedInteger(const char* name, long long value, long long min, long long max) const;
  template <class T>
  static long long Clamp(T bound) {
    constexpr auto kMax = std::numeric_limits<long long>::max();
    if constexpr (std::is_unsigned_v<T>) {
      return bound > static_cast<unsigned long long>(kMax) ? kMax : static_cast<long long>(bound);
    } else {
      return static_cast<long long>(bound);
    }
  }
  const XmlFile& file_;
  const tinyxml2::XMLElement& element_;
  std::set<std::string> read_;
};

// Throws ConfigError unless every child element's name is one of `allowed`.
void RequireChildNames(const XmlFile& file, const tinyxml2::XMLElement& parent,
                       const std::set<std::string>& allowed);

}  // namespace structloc::config
