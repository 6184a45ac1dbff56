// DDS Security for a participant: the files of one SROS2-style enclave
// (KEYSTORE/enclaves/IDENTITY, made by structloc_keystore) turned into the
// Fast DDS properties that enable authentication (PKI-DH), access control
// (signed governance and permissions) and encryption (AES-GCM-GMAC). Checks
// every file first, so that a component refuses to start naming the missing
// or unreadable one (fail closed) instead of running without security.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace structloc::dds_common {

struct SecurityOptions {
  std::string keystore;  // "" = DDS Security off
  std::string identity;  // the enclave's name under KEYSTORE/enclaves
  bool Enabled() const { return !keystore.empty(); }
  std::string EnclaveFolder() const { return keystore + "/enclaves/" + identity; }
};

// The largest file of an enclave we read (certificates and signed XML are a
// few kB): a larger one is an error naming the limit.
inline constexpr long long kMaxEnclaveFileBytes = 1 << 20;

// Property name/value pairs for the participant QoS. Throws
// config::ConfigError naming the enclave file that is missing, unreadable,
// empty or too large, or an identity that is not a plain name.
std::vector<std::pair<std::string, std::string>> SecurityProperties(const SecurityOptions& options);

}  // namespace structloc::dds_common
