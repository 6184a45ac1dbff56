// Enclave files -> Fast DDS security properties (see header).
#include "structloc/dds_common/security_enclave.hpp"

#include <cctype>
#include <filesystem>
#include <fstream>

#include "structloc/config/command_line.hpp"

namespace structloc::dds_common {
namespace {

struct EnclaveFile {
  const char* name;
  const char* meaning;
  const char* property;
};

// SROS2's file names; the properties of Fast DDS's builtin plugins.
constexpr EnclaveFile kFiles[] = {
    {"identity_ca.cert.pem", "the identity CA", "dds.sec.auth.builtin.PKI-DH.identity_ca"},
    {"cert.pem", "this identity's certificate", "dds.sec.auth.builtin.PKI-DH.identity_certificate"},
    {"key.pem", "this identity's private key", "dds.sec.auth.builtin.PKI-DH.private_key"},
    {"permissions_ca.cert.pem", "the permissions CA",
     "dds.sec.access.builtin.Access-Permissions.permissions_ca"},
    {"governance.p7s", "the signed governance",
     "dds.sec.access.builtin.Access-Permissions.governance"},
    {"permissions.p7s", "this identity's signed permissions",
     "dds.sec.access.builtin.Access-Permissions.permissions"},
};

void CheckIdentity(const std::string& identity) {
  bool plain = !identity.empty() && identity != "." && identity != "..";
  for (const char c : identity) {
    plain =
        plain && (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.');
  }
  if (!plain) {
    throw config::ConfigError("security identity '" + identity +
                              "' must be an enclave name (letters, digits, _ - .), e.g. "
                              "localisation");
  }
}

void CheckReadable(const std::filesystem::path& path, const EnclaveFile& file) {
  const std::string what = path.string() + " (" + file.meaning + ")";
  const std::string fix =
      "; make the keystore with structloc_keystore, or check --security-keystore "
      "and --security-identity";
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    throw config::ConfigError("DDS Security: " + what + " is missing" + fix);
  }
  const auto bytes = std::filesystem::file_size(path, error);
  if (error || bytes == 0) throw config::ConfigError("DDS Security: " + what + " is empty" + fix);
  if (static_cast<long long>(bytes) > kMaxEnclaveFileBytes) {
    throw config::ConfigError("DDS Security: " + what + " has " + std::to_string(bytes) +
                              " bytes, more than the limit of " +
                              std::to_string(kMaxEnclaveFileBytes) + " for an enclave file");
  }
  std::ifstream in(path);
  if (!in.good()) throw config::ConfigError("DDS Security: cannot read " + what + fix);
}

}  // namespace

std::vector<std::pair<std::string, std::string>> SecurityProperties(
    const SecurityOptions& options) {
  if (!options.Enabled()) return {};
  CheckIdentity(options.identity);
  const auto folder = std::filesystem::absolute(options.EnclaveFolder());
  std::error_code error;
  if (!std::filesystem::is_directory(folder, error)) {
    throw config::ConfigError("DDS Security: enclave folder " + folder.string() +
                              " does not exist (structloc_keystore makes "
                              "KEYSTORE/enclaves/{simulator,localisation,calibration,operator})");
  }
  std::vector<std::pair<std::string, std::string>> properties = {
      {"dds.sec.auth.plugin", "builtin.PKI-DH"},
      {"dds.sec.access.plugin", "builtin.Access-Permissions"},
      {"dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC"},
  };
  for (const auto& file : kFiles) {
    const auto path = folder / file.name;
    CheckReadable(path, file);
    properties.emplace_back(file.property, "file://" + path.string());
  }
  return properties;
}

}  // namespace structloc::dds_common
