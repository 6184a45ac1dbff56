// Robot parameter file reading, writing and validation, all from the one
// declaration of its keys.
#include "structloc/kinematics/robot_parameters.hpp"

#include "structloc/config/strict_xml.hpp"

namespace structloc::kinematics {

namespace {

const std::vector<std::pair<std::string, DriveKind>> kKindNames = {
    {"tricycle", DriveKind::kTricycle}, {"differential", DriveKind::kDifferential}};

void AddSensorMounting(config::OptionTable<RobotParameters>& t) {
  using R = RobotParameters;
  const config::Range mount = config::Range::Closed(-kMaxRobotLength_m, kMaxRobotLength_m);
  t.Number("sensor_x", &R::sensor, &geometry::Pose2D::x, mount, "m",
           "calibration fix sensor, ahead of the reference point")
      .Optional();
  t.Number("sensor_y", &R::sensor, &geometry::Pose2D::y, mount, "m", "... left of it").Optional();
  t.Number("sensor_theta", &R::sensor, &geometry::Pose2D::theta,
           config::Range::Closed(-geometry::kPi, geometry::kPi), "rad",
           "... its heading on the robot")
      .Optional();
}

// The incremental counter(s): ticks per revolution and the width they wrap at.
void AddCounters(config::OptionTable<RobotParameters>& t, const char* ticks_key,
                 const char* ticks_meaning, const char* bits_key, const char* bits_meaning) {
  using config::Range;
  using R = RobotParameters;
  t.Number(ticks_key, &R::traction_ticks_per_rev, Range::Closed(kMinTicksPerRev, kMaxTicksPerRev),
           "", ticks_meaning);
  t.Number(bits_key, &R::traction_counter_bits, Range::Closed(kMinCounterBits, kMaxCounterBits), "",
           bits_meaning);
}

config::OptionTable<RobotParameters> TricycleTable() {
  using config::Range;
  using R = RobotParameters;
  const Range length = Range::Closed(kMinRobotLength_m, kMaxRobotLength_m);
  config::OptionTable<R> t("robot",
                           "tricycle odometry, thesis 5.2 / EQ 46 (reference point: rear axle "
                           "middle)");
  t.Choice("kind", &R::kind, kKindNames, "drive kind (a file without it is a tricycle)").Optional();
  t.Number("wheel_radius", &R::wheel_radius, length, "m", "traction (front) wheel radius");
  t.Number("axle_distance", &R::axle_distance, length, "m", "front wheel axis to rear axle");
  t.Number("steering_offset", &R::steering_offset, Range::Open(-geometry::kPi, geometry::kPi),
           "rad", "steering angle at steering_zero_tick");
  AddCounters(t, "traction_ticks_per_rev", "encoder ticks per wheel revolution",
              "traction_counter_bits", "the traction counter wraps at 2^bits");
  t.Number("steering_rad_per_tick", &R::steering_rad_per_tick,
           Range::Magnitude(kMinSteeringRadPerTick, kMaxSteeringRadPerTick), "rad",
           "steering angle per encoder tick (either sign)");
  t.Number("steering_zero_tick", &R::steering_zero_tick,
           Range::Closed(-kMaxSteeringZeroTick, kMaxSteeringZeroTick), "",
           "steering encoder reading at steering_offset");
  AddSensorMounting(t);
  return t;
}

config::OptionTable<RobotParameters> DifferentialTable() {
  using config::Range;
  using R = RobotParameters;
  const Range length = Range::Closed(kMinRobotLength_m, kMaxRobotLength_m);
  config::OptionTable<R> t("robot",
                           "differential-drive odometry (reference point: wheel axle middle)");
  t.Choice("kind", &R::kind, kKindNames, "drive kind");
  t.Number("left_wheel_radius", &R::left_wheel_radius, length, "m", "left wheel radius");
  t.Number("right_wheel_radius", &R::right_wheel_radius, length, "m", "right wheel radius");
  t.Number("wheel_separation", &R::wheel_separation, length, "m",
           "distance between the wheels' contact points");
  AddCounters(t, "ticks_per_rev", "encoder ticks per wheel revolution (both wheels)",
              "counter_bits", "both wheel counters wrap at 2^bits");
  AddSensorMounting(t);
  return t;
}

}  // namespace

config::OptionTable<RobotParameters> RobotParameterTable(DriveKind kind) {
  auto t = kind == DriveKind::kDifferential ? DifferentialTable() : TricycleTable();
  t.Wording([](const std::string& key, const std::string& value, const std::string& valid,
               const std::string& unit) {
    return key + " = " + value + " is implausible; it must be " + valid +
           (unit.empty() ? "" : " " + unit);
  });
  return t;
}

void PrintRobotParameters(std::ostream& out) {
  out << "<robot>: one element; every key is required unless marked [optional]; columns: key, "
         "default, unit, valid values, meaning\nkind=\"tricycle\" (or no kind):\n";
  RobotParameterTable().Print(out, RobotParameters{});
  RobotParameters differential;
  differential.kind = DriveKind::kDifferential;
  out << "kind=\"differential\":\n";
  RobotParameterTable(DriveKind::kDifferential).Print(out, differential);
}

void RobotParameters::Validate() const {
  RobotParameterTable(kind).Validate(*this);
}

int64_t RobotParameters::TickDelta(uint64_t previous, uint64_t current) const {
  const uint64_t modulus = uint64_t{1} << traction_counter_bits;
  const uint64_t mask = modulus - 1;
  const uint64_t diff = (current - previous) & mask;
  // Differences above half the range are backwards motion across the wrap;
  // modulus - diff <= 2^62 always fits (2^63 itself, for 63 bits, would not).
  return diff >= modulus / 2 ? -static_cast<int64_t>(modulus - diff) : static_cast<int64_t>(diff);
}

uint64_t RobotParameters::MaxTractionTick() const {
  return (uint64_t{1} << traction_counter_bits) - 1;
}

RobotParameters LoadRobotParameters(const std::string& path) {
  const auto file = config::XmlFile::Load(path);
  const auto& root = file.Root("robot");
  if (root.FirstChildElement() != nullptr) file.Fail(root, "takes no child elements");
  RobotParameters p;
  const char* kind = root.Attribute("kind");
  if (kind != nullptr && std::string(kind) == "differential") p.kind = DriveKind::kDifferential;
  RobotParameterTable(p.kind).Load(file, root, p);
  return p;
}

std::string XmlCommentBody(const std::string& text) {
  std::string body;
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '-' && !body.empty() && body.back() == '-') body += ' ';
    body += byte < 0x20 || byte == 0x7f ? '?' : c;
  }
  if (!body.empty() && body.back() == '-') body += ' ';
  return body;
}

void WriteRobotParameters(const RobotParameters& p, std::ostream& out, const std::string& comment) {
  out << "<?xml version=\"1.0\"?>\n<!-- " << XmlCommentBody(comment) << " -->\n<robot";
  size_t column = 6;  // attributes wrapped within 100 columns, continued under the first
  for (const auto& [key, value] : RobotParameterTable(p.kind).Values(p)) {
    const std::string attribute = key + "=\"" + value + "\"";
    if (column > 6 && column + 1 + attribute.size() > 100) {
      out << "\n      ";
      column = 6;
    }
    out << " " << attribute;
    column += 1 + attribute.size();
  }
  out << "/>\n";
}

}  // namespace structloc::kinematics
