// The DDS domain of every test that starts participants, in one table. Each is
// distinct, so ctest -j never lets two test files hear each other (tests of
// one file share their domain and a ctest RESOURCE_LOCK, so they never overlap),
// and each is at most 101: Fast DDS derives its UDP ports from the domain
// (7400 + 250 x domain + offsets) and domains above 101 reach Linux's
// ephemeral port range (32768-60999), where any process's outgoing socket can
// hold a discovery port and cut a participant off (see domain_ports.hpp).
#pragma once

#include <array>

namespace structloc::testing::domains {

inline constexpr int kIdlRoundtrip = 60;
inline constexpr int kQosProfiles = 61;
inline constexpr int kComponentsProcess = 62;
inline constexpr int kComponentsBrokenProfile = 63;
inline constexpr int kLaunch = 64;
inline constexpr int kSimulatorComponent = 65;
inline constexpr int kLocalisationIntegration = 66;
inline constexpr int kLocalisationBadInput = 67;
inline constexpr int kLocalisationRestart = 68;
inline constexpr int kCalibrationComponent = 69;
inline constexpr int kBadInputLocalisation = 70;
inline constexpr int kBadInputLocalisationSecond = 71;
inline constexpr int kBadInputConfig = 72;
inline constexpr int kBadInputCalibration = 73;
inline constexpr int kDomainPorts = 74;
inline constexpr int kLocalisationGlobalStart = 75;
inline constexpr int kTwoRobots = 76;
inline constexpr int kLaunchRun = 77;
inline constexpr int kComponentTeardown = 81;
// tests/install/install_test.sh (a script: tests/CMakeLists.txt passes it 82).
inline constexpr int kInstallTest = 82;
inline constexpr int kDdsSecurity = 83;
// tests/security/secure_demo_test.sh (a script: tests/CMakeLists.txt passes it 84).
inline constexpr int kSecureDemo = 84;
// tests/system/repeated_faults_test.cpp: the simulator's kills on 85, the
// localisation's on 88, the calibration's on 89.
inline constexpr int kRepeatedFaults = 85;
inline constexpr int kRepeatedFaultsLocalisation = 88;
inline constexpr int kRepeatedFaultsCalibration = 89;
// tests/multihost/netns_packet_loss_test.sh (a script: tests/CMakeLists.txt passes it 87).
inline constexpr int kPacketLoss = 87;
// tests/multihost/netns_multihost_test.sh (a script: tests/CMakeLists.txt passes it 78).
inline constexpr int kNetnsMultihost = 78;
// tests/interop/cyclone_interop_test.sh (a script: tests/CMakeLists.txt passes it 79).
inline constexpr int kCycloneInterop = 79;
inline constexpr int kFleetBenchmark = 80;
// structloc_fleet_benchmark --layout domains: robot k on kFleetDomainsFirst + k - 1,
// a range no test uses.
inline constexpr int kFleetDomainsFirst = 21;
inline constexpr int kFleetDomainsMost = 30;
inline constexpr int kLatencyBenchmark = 90;
inline constexpr int kSoakBenchmark = 86;
inline constexpr int kRecordCli = 91;
inline constexpr int kCpuWakeLatency = 92;
inline constexpr int kLateLaser = 93;

inline constexpr std::array kAll = {kIdlRoundtrip,
                                    kQosProfiles,
                                    kComponentsProcess,
                                    kComponentsBrokenProfile,
                                    kLaunch,
                                    kSimulatorComponent,
                                    kLocalisationIntegration,
                                    kLocalisationBadInput,
                                    kLocalisationRestart,
                                    kCalibrationComponent,
                                    kBadInputLocalisation,
                                    kBadInputLocalisationSecond,
                                    kBadInputConfig,
                                    kBadInputCalibration,
                                    kDomainPorts,
                                    kLocalisationGlobalStart,
                                    kTwoRobots,
                                    kLaunchRun,
                                    kComponentTeardown,
                                    kInstallTest,
                                    kDdsSecurity,
                                    kSecureDemo,
                                    kRepeatedFaults,
                                    kRepeatedFaultsLocalisation,
                                    kRepeatedFaultsCalibration,
                                    kPacketLoss,
                                    kNetnsMultihost,
                                    kCycloneInterop,
                                    kFleetBenchmark,
                                    kLatencyBenchmark,
                                    kSoakBenchmark,
                                    kRecordCli,
                                    kCpuWakeLatency,
                                    kLateLaser};

constexpr bool AllDistinctAndSafe() {
  for (size_t i = 0; i < kAll.size(); ++i) {
    if (kAll[i] < 0 || kAll[i] > 101) return false;
    for (size_t j = i + 1; j < kAll.size(); ++j) {
      if (kAll[i] == kAll[j]) return false;
    }
  }
  return true;
}
static_assert(AllDistinctAndSafe(), "test domains must be distinct and in 0..101");
static_assert(kFleetDomainsFirst + kFleetDomainsMost - 1 < kIdlRoundtrip,
              "the fleet's domains must stay below every test's");

}  // namespace structloc::testing::domains
