// Implementation of the strict XML reader: parsing, typed attributes, errors with file:line.
#include "structloc/config/strict_xml.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "structloc/config/strict_number.hpp"

namespace structloc::config {

XmlFile XmlFile::Load(const std::string& path, size_t max_bytes) {
  std::error_code ignored;
  if (std::filesystem::is_directory(path, ignored)) {
    throw ConfigError(path + ": is a folder, not an XML file");
  }
  std::ifstream probe(path);
  if (!probe) throw ConfigError(path + ": cannot open file");
  const auto bytes = std::filesystem::file_size(path, ignored);
  if (!ignored && bytes > max_bytes) {
    throw ConfigError(path + ": " + std::to_string(bytes) + " bytes, over the limit of " +
                      std::to_string(max_bytes) + " bytes for an XML file");
  }
  XmlFile file;
  file.path_ = path;
  file.doc_ = std::make_unique<tinyxml2::XMLDocument>();
  if (file.doc_->LoadFile(path.c_str()) != tinyxml2::XML_SUCCESS) {
    std::ostringstream msg;
    msg << path << ":" << file.doc_->ErrorLineNum() << ": malformed XML: " << file.doc_->ErrorStr();
    throw ConfigError(msg.str());
  }
  for (const auto* node = file.doc_->FirstChild(); node != nullptr; node = node->NextSibling()) {
    if (node->ToUnknown() != nullptr) {
      throw ConfigError(path + ":" + std::to_string(node->GetLineNum()) +
                        ": a document type declaration (<!DOCTYPE ...>) is refused: structloc "
                        "files define no entities and read no external ones");
    }
  }
  if (file.doc_->RootElement() == nullptr) throw ConfigError(path + ": no root element");
  if (const auto* second = file.doc_->RootElement()->NextSiblingElement()) {
    file.Fail(*second, "a second root element after </" +
                           std::string(file.doc_->RootElement()->Name()) +
                           ">; a file holds exactly one");
  }
  return file;
}

const tinyxml2::XMLElement& XmlFile::Root() const {
  return *doc_->RootElement();
}

const tinyxml2::XMLElement& XmlFile::Root(const std::string& expected_name) const {
  const auto& root = Root();
  if (expected_name != root.Name()) {
    Fail(root,
         "root element is <" + std::string(root.Name()) + ">, expected <" + expected_name + ">");
  }
  return root;
}

void XmlFile::Fail(const tinyxml2::XMLElement& where, const std::string& what) const {
  std::ostringstream msg;
  msg << path_ << ":" << where.GetLineNum() << ": <" << where.Name() << ">: " << what;
  throw ConfigError(msg.str());
}

AttributeReader::AttributeReader(const XmlFile& file, const tinyxml2::XMLElement& element)
    : file_(file), element_(element) {}

bool AttributeReader::Has(const char* name) const {
  return element_.Attribute(name) != nullptr;
}

const char* AttributeReader::Raw(const char* name) {
  read_.insert(name);
  return element_.Attribute(name);
}

void AttributeReader::Fail(const std::string& what) const {
  file_.Fail(element_, what);
}

std::optional<double> AttributeReader::OptionalDouble(const char* name) {
  const char* raw = Raw(name);
  if (raw == nullptr) return std::nullopt;
  const auto value = ParseFiniteDouble(raw);
  if (!value) {
    Fail(std::string("attribute ") + name + "=\"" + raw +
         "\" is not a finite number (decimal digits only)");
  }
  return *value;
}

double AttributeReader::Double(const char* name) {
  auto value = OptionalDouble(name);
  if (!value) Fail(std::string("missing attribute ") + name);
  return *value;
}

double AttributeReader::PositiveDouble(const char* name) {
  const double value = Double(name);
  if (!(value > 0.0)) Fail(std::string("attribute ") + name + " must be > 0");
  return value;
}

double AttributeReader::NonNegativeDouble(const char* name) {
  const double value = Double(name);
  if (value < 0.0) Fail(std::string("attribute ") + name + " must be >= 0");
  return value;
}

std::optional<long long> AttributeReader::OptionalInteger(const char* name) {
  const char* raw = Raw(name);
  if (raw == nullptr) return std::nullopt;
  const auto value = ParseInteger(raw);
  if (!value) {
    Fail(std::string("attribute ") + name + "=\"" + raw +
         "\" is not an integer (decimal digits, within 64 bits)");
  }
  return *value;
}

long long AttributeReader::Integer(const char* name) {
  auto value = OptionalInteger(name);
  if (!value) Fail(std::string("missing attribute ") + name);
  return *value;
}

double AttributeReader::DoubleIn(const char* name, double min, double max) {
  const double value = Double(name);
  if (value < min || value > max) {
    std::ostringstream msg;
    msg << "attribute " << name << " must be from " << min << " to " << max << ", not \""
        << element_.Attribute(name) << "\"";
    Fail(msg.str());
  }
  return value;
}

long long AttributeReader::CheckedInteger(const char* name, long long value, long long min,
                                          long long max) const {
  if (value < min || value > max) {
    Fail(std::string("attribute ") + name + " must be an integer from " + std::to_string(min) +
         " to " + std::to_string(max) + ", not \"" + element_.Attribute(name) + "\"");
  }
  return value;
}

bool AttributeReader::Bool(const char* name) {
  const std::string value = String(name);
  if (value == "true") return true;
  if (value == "false") return false;
  Fail(std::string("attribute ") + name + "=\"" + value + "\" must be true or false");
}

std::optional<std::string> AttributeReader::OptionalString(const char* name) {
  const char* raw = Raw(name);
  if (raw == nullptr) return std::nullopt;
  return std::string(raw);
}

std::string AttributeReader::String(const char* name) {
  auto value = OptionalString(name);
  if (!value) Fail(std::string("missing attribute ") + name);
  return *value;
}

void AttributeReader::Finish() const {
  std::string unknown;
  for (const auto* a = element_.FirstAttribute(); a != nullptr; a = a->Next()) {
    if (read_.count(a->Name()) == 0)
      unknown += (unknown.empty() ? "" : ", ") + std::string(a->Name());
  }
  if (!unknown.empty()) Fail("unknown attribute(s): " + unknown);
}

void RequireChildNames(const XmlFile& file, const tinyxml2::XMLElement& parent,
                       const std::set<std::string>& allowed) {
  for (const auto* child = parent.FirstChildElement(); child != nullptr;
       child = child->NextSiblingElement()) {
    if (allowed.count(child->Name()) == 0) {
      std::string names;
      for (const auto& a : allowed) names += (names.empty() ? "" : ", ") + a;
      file.Fail(*child,
                "unknown element inside <" + std::string(parent.Name()) + ">; allowed: " + names);
    }
  }
}

}  // namespace structloc::config
