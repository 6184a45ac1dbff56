// Last calibration result on disk (see header).
#include "structloc/calibration/last_result_file.hpp"

#include <fastcdr/exceptions/Exception.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "structloc/config/output_file.hpp"

namespace structloc::calibration {
namespace {

bool Finite(const structloc_msgs::msg::RobotParameters& p) {
  for (const double v :
       {p.wheel_radius_m(), p.axle_distance_m(), p.steering_offset_rad(), p.steering_rad_per_tick(),
        p.sensor_x_m(), p.sensor_y_m(), p.sensor_theta_rad(), p.left_wheel_radius_m(),
        p.right_wheel_radius_m(), p.wheel_separation_m()}) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

}  // namespace

std::string SaveLastResult(const std::string& path,
                           const structloc_msgs::msg::CalibrationResult& result) {
  structloc_msgs::msg::CalibrationResultPubSubType type;
  auto copy = result;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(type.getSerializedSizeProvider(&copy)());
  if (!type.serialize(&copy, &payload)) return "cannot encode the result for " + path;
  try {
    config::OutputFile file(path);
    file.Stream().write(reinterpret_cast<const char*>(payload.data), payload.length);
    file.Commit();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

std::optional<structloc_msgs::msg::CalibrationResult> LoadLastResult(const std::string& path,
                                                                     std::string& why) {
  std::error_code error;
  const auto bytes = std::filesystem::file_size(path, error);
  if (error) {
    why = path + ": " + error.message();
    return std::nullopt;
  }
  if (bytes == 0 || static_cast<long long>(bytes) > kMaxLastResultBytes) {
    why = path + " has " + std::to_string(bytes) + " bytes; a saved result has 1 to " +
          std::to_string(kMaxLastResultBytes);
    return std::nullopt;
  }
  std::ifstream in(path, std::ios::binary);
  const std::vector<char> data((std::istreambuf_iterator<char>(in)),
                               std::istreambuf_iterator<char>());
  if (data.size() != bytes) {
    why = "cannot read " + path;
    return std::nullopt;
  }
  eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<uint32_t>(data.size()));
  std::copy(data.begin(), data.end(), payload.data);
  payload.length = static_cast<uint32_t>(data.size());
  structloc_msgs::msg::CalibrationResultPubSubType type;
  structloc_msgs::msg::CalibrationResult result;
  bool decoded = false;
  try {
    decoded = type.deserialize(&payload, &result);
  } catch (const eprosima::fastcdr::exception::Exception&) {
    decoded = false;  // e.g. a boolean that is neither 0 nor 1
  }
  if (!decoded) {
    why = path + " is not a saved calibration result (CDR of structloc_msgs/CalibrationResult)";
    return std::nullopt;
  }
  bool finite = Finite(result.parameters()) && Finite(result.standard_deviations());
  for (const double c : result.covariance()) finite = finite && std::isfinite(c);
  if (!finite) {
    why = path + " holds a parameter, deviation or covariance that is not a finite number";
    return std::nullopt;
  }
  return result;
}

}  // namespace structloc::calibration
