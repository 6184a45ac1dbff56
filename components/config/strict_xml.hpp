// Strict reading of our XML files (maps, scenarios, parameters, launch): every
// problem names the file and line, unknown attributes and elements are errors,
// missing or non-numeric values are errors. DDS-free.
#pragma once

#include <tinyxml2.h>

#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>

namespace structloc::config {

// A configuration problem a user can act on: "FILE:LINE: what is wrong".
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A parsed XML file that remembers its path for error messages.
class XmlFile {
 public:
  // Throws ConfigError when the file is missing, unreadable or not well-formed.
  static XmlFile Load(const std::string& path);

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
  long long Integer(const char* name);
  std::optional<long long> OptionalInteger(const char* name);
  bool Bool(const char* name);
  std::string String(const char* name);
  std::optional<std::string> OptionalString(const char* name);
  bool Has(const char* name) const;

  // Throws ConfigError naming every attribute that was not read.
  void Finish() const;
  [[noreturn]] void Fail(const std::string& what) const;

 private:
  const char* Raw(const char* name);
  const XmlFile& file_;
  const tinyxml2::XMLElement& element_;
  std::set<std::string> read_;
};

// Throws ConfigError unless every child element's name is one of `allowed`.
void RequireChildNames(const XmlFile& file, const tinyxml2::XMLElement& parent,
                       const std::set<std::string>& allowed);

}  // namespace structloc::config
