// Helpers for tests/peers/mrpt_pf_localization.sh (the MRPT particle-filter
// peer). Compiled on the fly by that script into its temporary directory
// against Debian's libmrpt-dev (2.5.x); MRPT is never a dependency of the
// product. Three subcommands:
//
//   rawlog --log EVAL.log --out OUT.rawlog --a1 M_PER_M --a2 M_PER_DEG
//          --a3 DEG_PER_M --a4 DEG_PER_DEG --min-xy M --min-phi DEG
//     The evaluation log `structloc synthesise-odometry` writes (ODOM +
//     ROBOTLASER1 lines, one pair per scan) as an MRPT action/sensory-frame
//     rawlog. Per scan: a CObservation2DRangeScan with the scan's OWN ipc
//     timestamp, beams exactly as in the log (beam 0 at the line's
//     start_angle, N beams at angular_res, i.e. aperture (N-1)*angular_res,
//     counter-clockwise), readings at or beyond the line's maximum_range (the
//     no-return values 81.83 / 81.91 m) marked invalid, and the sensor pose
//     taken from the line's laser pose relative to its robot pose; and a
//     CActionRobotMovement2D made by computeFromOdometry from the odometry
//     increment since the previous scan (the robot poses of the ROBOTLASER1
//     lines, i.e. the odometry at scan time) with MRPT's probabilistic motion
//     model (mmGaussian): std of x and y = min_xy + a1*d + a2*|dphi|, std of
//     phi = min_phi + a3*d + a4*|dphi| (d = distance, dphi = turn of the
//     step), so the noise grows with the step and never falls below the floor.
//     pf-localization does not run the filter on the first pair it reads
//     (step 0 only logs the initial particles), so the first scan is written
//     twice, both times with a zero odometry increment: the filter then sees
//     every scan, and its estimate for scan k is its (k+1)-th "PDF estimation".
//     (MRPT's Thrun model, mmThrun, cannot be used: in MRPT 2.5 the filter
//     draws increments from the action's CPosePDFParticles, whose weights are
//     all exp(0) = 1, so every particle gets the first pre-drawn increment and
//     the motion noise is lost.)
//
//   grid-yaml --yaml MAP.yaml --out MAP.gridmap.gz --decimation K
//          [--std-hit M --max-corr M --z-hit P --z-random P --max-range M]
//     A map_server grid (what `structloc map export` and `map grid` write) as
//     a .gridmap.gz with the likelihood-field options baked in (pf-localization
//     reads them from the .gridmap and ignores the ini's for it). Loaded with
//     loadFromROSMapServerYAML, which rounds the YAML origin to a whole cell;
//     prints "shift DX DY": the rounded minus the YAML origin, i.e. a world
//     point p is at p + (DX, DY) in the saved grid. The caller adds the shift
//     to the initial particle box and subtracts it from every estimate.
//
//   grid-hits --log EVAL.log --truth TRUTH.tum --out HITS.gridmap.gz
//          --decimation K [--resolution M --max-range M ...likelihood options]
//     A grid whose only occupied cells are those where the corrected log's
//     beams end (at least one reading shorter than --max-range, default 20 m
//     like `structloc map grid`, projected from the TRUE pose of its scan and
//     the sensor pose of its line); every other cell is unknown. Its origin is
//     a whole number of cells, so it needs no shift (prints "shift 0 0").
//
// Exit status: 0 done, 1 bad input or failure, 2 usage.
#include <mrpt/containers/yaml.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/io/CFileOutputStream.h>
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/serialization/CArchive.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct Scan {
  double t = 0;
  double start = 0, fov = 0, res = 0, max_range = 0;
  std::vector<double> ranges;
  mrpt::poses::CPose2D laser, robot;  // in the odometry frame
};

[[noreturn]] void die(const std::string& what, int code = 1) {
  std::cerr << "mrpt_peer_tools: " << what << "\n";
  std::exit(code);
}

// ROBOTLASER1 laser_type start_angle fov angular_res max_range accuracy
// remission_mode n r_1..r_n m rem_1..rem_m laser_x laser_y laser_theta
// robot_x robot_y robot_theta tv rv fsd ssd turn_axis ipc_ts host logger_ts
std::vector<Scan> read_eval_log(const std::string& path) {
  std::ifstream in(path);
  if (!in) die("cannot read " + path);
  std::vector<Scan> scans;
  std::string line;
  size_t lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    if (line.rfind("ROBOTLASER1 ", 0) != 0) continue;
    std::istringstream s(line.substr(12));
    Scan sc;
    int type = 0, remission_mode = 0;
    size_t n = 0, m = 0;
    double accuracy = 0;
    s >> type >> sc.start >> sc.fov >> sc.res >> sc.max_range >> accuracy >> remission_mode >> n;
    if (!s || n < 2 || n > 100000)
      die(path + ":" + std::to_string(lineno) + ": bad ROBOTLASER1 header");
    sc.ranges.resize(n);
    for (auto& r : sc.ranges) s >> r;
    s >> m;
    for (size_t i = 0; i < m; ++i) {
      double rem;
      s >> rem;
    }
    double lx, ly, lth, rx, ry, rth, tv, rv, fsd, ssd, ta;
    std::string host;
    s >> lx >> ly >> lth >> rx >> ry >> rth >> tv >> rv >> fsd >> ssd >> ta >> sc.t >> host;
    if (!s) die(path + ":" + std::to_string(lineno) + ": truncated ROBOTLASER1 line");
    sc.laser = mrpt::poses::CPose2D(lx, ly, lth);
    sc.robot = mrpt::poses::CPose2D(rx, ry, rth);
    // Beam i is at start_angle + i * angular_res, as for structloc's reader;
    // the fov field is only compared (it may differ in the last digits:
    // 0.008727 * 359 vs 3.132866 for 0.5-deg scans).
    static bool told = false;
    if (!told && std::abs((n - 1) * sc.res - sc.fov) > 1e-6) {
      told = true;
      std::cerr << "mrpt_peer_tools: " << path << ":" << lineno << ": fov " << sc.fov
                << " differs from (N-1)*angular_res = " << (n - 1) * sc.res
                << " (rounding of the written fields); the beams follow angular_res\n";
    }
    scans.push_back(std::move(sc));
  }
  if (scans.empty()) die(path + ": no ROBOTLASER1 lines");
  return scans;
}

// Sensor pose on the robot: the line's laser pose relative to its robot pose,
// turned so that MRPT's symmetric beam layout (-aperture/2 .. +aperture/2)
// puts beam 0 at start_angle.
mrpt::obs::CObservation2DRangeScan make_scan(const Scan& sc) {
  mrpt::obs::CObservation2DRangeScan o;
  const size_t n = sc.ranges.size();
  const double aperture = (n - 1) * sc.res;
  const mrpt::poses::CPose2D mount = sc.laser - sc.robot;  // robot^-1 (+) laser
  o.sensorLabel = "LASER";
  o.timestamp = mrpt::Clock::fromDouble(sc.t);
  o.aperture = static_cast<float>(aperture);
  o.rightToLeft = true;
  o.maxRange = static_cast<float>(sc.max_range);
  o.stdError = 0.01f;
  o.sensorPose =
      mrpt::poses::CPose3D(mount.x(), mount.y(), 0.0,
                           mrpt::math::wrapToPi(mount.phi() + sc.start + 0.5 * aperture), 0.0, 0.0);
  o.resizeScan(n);
  for (size_t i = 0; i < n; ++i) {
    const double r = sc.ranges[i];
    const bool valid = r > 0.0 && r < sc.max_range;
    o.setScanRange(i, static_cast<float>(valid ? r : sc.max_range));
    o.setScanRangeValidity(i, valid);
  }
  return o;
}

std::map<std::string, std::string> parse(int argc, char** argv, int first) {
  std::map<std::string, std::string> a;
  for (int i = first; i < argc; i += 2) {
    const std::string k = argv[i];
    if (k.rfind("--", 0) != 0 || i + 1 >= argc) die("bad argument '" + k + "'", 2);
    a[k.substr(2)] = argv[i + 1];
  }
  return a;
}

std::string need(const std::map<std::string, std::string>& a, const std::string& k) {
  auto it = a.find(k);
  if (it == a.end()) die("--" + k + " is required", 2);
  return it->second;
}

double num(const std::map<std::string, std::string>& a, const std::string& k, double dflt) {
  auto it = a.find(k);
  if (it == a.end()) return dflt;
  try {
    return std::stod(it->second);
  } catch (...) {
    die("--" + k + " needs a number", 2);
  }
}

int cmd_rawlog(const std::map<std::string, std::string>& a) {
  const auto scans = read_eval_log(need(a, "log"));
  mrpt::obs::CActionRobotMovement2D::TMotionModelOptions mm;
  mm.modelSelection = mrpt::obs::CActionRobotMovement2D::mmGaussian;
  mm.gaussianModel.a1 = num(a, "a1", NAN);                             // m per m
  mm.gaussianModel.a2 = mrpt::RAD2DEG(num(a, "a2", NAN));              // m per deg -> m per rad
  mm.gaussianModel.a3 = mrpt::DEG2RAD(num(a, "a3", NAN));              // deg per m -> rad per m
  mm.gaussianModel.a4 = num(a, "a4", NAN);                             // deg per deg
  mm.gaussianModel.minStdXY = num(a, "min-xy", NAN);                   // m
  mm.gaussianModel.minStdPHI = mrpt::DEG2RAD(num(a, "min-phi", NAN));  // deg -> rad
  for (double v : {mm.gaussianModel.a1, mm.gaussianModel.a2, mm.gaussianModel.a3,
                   mm.gaussianModel.a4, mm.gaussianModel.minStdXY, mm.gaussianModel.minStdPHI})
    if (!(v >= 0)) die("--a1 --a2 --a3 --a4 --min-xy --min-phi are required, >= 0", 2);

  mrpt::io::CFileOutputStream f;
  if (!f.open(need(a, "out"))) die("cannot write " + need(a, "out"));
  auto ar = mrpt::serialization::archiveFrom(f);
  size_t invalid = 0, beams = 0;
  for (size_t k = 0; k <= scans.size(); ++k) {
    // k = 0: the first scan again, for pf-localization's step 0, which
    // runs no filter step.
    const Scan& sc = scans[k == 0 ? 0 : k - 1];
    const mrpt::poses::CPose2D incr =
        k <= 1 ? mrpt::poses::CPose2D() : sc.robot - scans[k - 2].robot;
    mrpt::obs::CActionRobotMovement2D act;
    act.computeFromOdometry(incr, mm);
    act.timestamp = mrpt::Clock::fromDouble(sc.t);
    mrpt::obs::CActionCollection acts;
    acts.insert(act);
    auto obs = mrpt::obs::CObservation2DRangeScan::Create(make_scan(sc));
    if (k > 0)
      for (size_t i = 0; i < obs->getScanSize(); ++i, ++beams)
        invalid += !obs->getScanRangeValidity(i);
    mrpt::obs::CSensoryFrame sf;
    sf.insert(obs);
    ar << acts << sf;
  }
  const auto& s0 = scans.front();
  const auto probe = make_scan(s0);
  std::printf(
      "rawlog: %zu scans (+1 lead-in pair), %zu beams/scan, beam 0 at %.4f deg, aperture %.4f deg, "
      "sensor yaw %.4f deg, %zu of %zu readings invalid (>= %.2f m or <= 0)\n",
      scans.size(), s0.ranges.size(), mrpt::RAD2DEG(probe.sensorPose.yaw() - 0.5 * probe.aperture),
      mrpt::RAD2DEG(probe.aperture), mrpt::RAD2DEG(probe.sensorPose.yaw()), invalid, beams,
      s0.max_range);
  return 0;
}

void set_likelihood(mrpt::maps::COccupancyGridMap2D& g,
                    const std::map<std::string, std::string>& a) {
  auto& lo = g.likelihoodOptions;
  lo.likelihoodMethod = mrpt::maps::COccupancyGridMap2D::lmLikelihoodField_Thrun;
  lo.LF_stdHit = static_cast<float>(num(a, "std-hit", 0.05));
  lo.LF_maxCorrsDistance = static_cast<float>(num(a, "max-corr", 0.30));
  lo.LF_zHit = static_cast<float>(num(a, "z-hit", 0.95));
  lo.LF_zRandom = static_cast<float>(num(a, "z-random", 0.05));
  lo.LF_maxRange = static_cast<float>(num(a, "lf-max-range", 80.0));
  const double decimation = num(a, "decimation", 0);
  if (!(decimation >= 1)) die("--decimation K (>= 1) is required", 2);
  lo.LF_decimation = static_cast<uint32_t>(decimation);
  lo.LF_useSquareDist = false;
  lo.LF_alternateAverageMethod = false;
  lo.enableLikelihoodCache = true;
}

void save_grid(const mrpt::maps::COccupancyGridMap2D& g, const std::string& out) {
  mrpt::io::CFileGZOutputStream f;
  if (!f.open(out)) die("cannot write " + out);
  mrpt::serialization::archiveFrom(f) << g;
  // Read it back: the options must survive the file.
  mrpt::maps::COccupancyGridMap2D back;
  f.close();
  mrpt::io::CFileGZInputStream fi(out);
  mrpt::serialization::archiveFrom(fi) >> back;
  const auto& lo = back.likelihoodOptions;
  std::printf(
      "grid %s: %u x %u cells of %.3f m, x %.4f..%.4f, y %.4f..%.4f; likelihood field: method %d, "
      "stdHit %.3f, maxCorrs %.2f, zHit %.2f, zRandom %.2f, maxRange %.1f, decimation %u, cache "
      "%d\n",
      out.c_str(), back.getSizeX(), back.getSizeY(), back.getResolution(), back.getXMin(),
      back.getXMax(), back.getYMin(), back.getYMax(), int(lo.likelihoodMethod), lo.LF_stdHit,
      lo.LF_maxCorrsDistance, lo.LF_zHit, lo.LF_zRandom, lo.LF_maxRange, lo.LF_decimation,
      int(lo.enableLikelihoodCache));
}

int cmd_grid_yaml(const std::map<std::string, std::string>& a) {
  const std::string yaml = need(a, "yaml");
  mrpt::maps::COccupancyGridMap2D g;
  if (!g.loadFromROSMapServerYAML(yaml)) die("cannot load " + yaml);
  const auto y = mrpt::containers::yaml::FromFile(yaml);
  const auto origin = y["origin"].toStdVector<double>();
  if (origin.size() >= 3 && std::abs(origin[2]) > 1e-9)
    die(yaml + ": a rotated origin is not supported by loadFromROSMapServerYAML");
  set_likelihood(g, a);
  save_grid(g, need(a, "out"));
  std::printf("shift %.6f %.6f\n", g.getXMin() - origin.at(0), g.getYMin() - origin.at(1));
  return 0;
}

std::vector<std::pair<double, mrpt::poses::CPose2D>> read_tum(const std::string& path) {
  std::ifstream in(path);
  if (!in) die("cannot read " + path);
  std::vector<std::pair<double, mrpt::poses::CPose2D>> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    double t, x, y, z, qx, qy, qz, qw;
    if (!(s >> t >> x >> y >> z >> qx >> qy >> qz >> qw)) die(path + ": bad TUM line: " + line);
    out.emplace_back(
        t, mrpt::poses::CPose2D(x, y,
                                std::atan2(2 * (qw * qz + qx * qy), 1 - 2 * (qy * qy + qz * qz))));
  }
  return out;
}

int cmd_grid_hits(const std::map<std::string, std::string>& a) {
  const auto scans = read_eval_log(need(a, "log"));
  const auto truth = read_tum(need(a, "truth"));
  if (truth.size() != scans.size())
    die("the truth has " + std::to_string(truth.size()) + " poses for " +
        std::to_string(scans.size()) + " scans");
  const double res = num(a, "resolution", 0.05), max_range = num(a, "max-range", 20.0);
  std::vector<mrpt::math::TPoint2D> hits;
  for (size_t k = 0; k < scans.size(); ++k) {
    const auto& sc = scans[k];
    if (std::abs(truth[k].first - sc.t) > 1e-4)
      die("truth and log stamps differ at scan " + std::to_string(k));
    const mrpt::poses::CPose2D laser = truth[k].second + (sc.laser - sc.robot);
    for (size_t i = 0; i < sc.ranges.size(); ++i) {
      const double r = sc.ranges[i];
      if (!(r > 0.0 && r < sc.max_range && r < max_range)) continue;
      const double ang = sc.start + i * sc.res;
      double gx, gy;
      laser.composePoint(r * std::cos(ang), r * std::sin(ang), gx, gy);
      hits.emplace_back(gx, gy);
    }
  }
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const auto& p : hits)
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  for (const auto& [t, p] : truth)
    x0 = std::min(x0, p.x()), x1 = std::max(x1, p.x()), y0 = std::min(y0, p.y()),
    y1 = std::max(y1, p.y());
  // Whole cells, with a 1 m border: setSize then keeps them exactly.
  x0 = res * std::floor(x0 / res - 20), y0 = res * std::floor(y0 / res - 20);
  x1 = res * std::ceil(x1 / res + 20), y1 = res * std::ceil(y1 / res + 20);
  mrpt::maps::COccupancyGridMap2D g;
  g.setSize(x0, x1, y0, y1, res, 0.5f);
  size_t occupied = 0;
  for (const auto& p : hits) {
    const int cx = static_cast<int>(std::floor((p.x - g.getXMin()) / res));
    const int cy = static_cast<int>(std::floor((p.y - g.getYMin()) / res));
    if (cx < 0 || cy < 0 || cx >= int(g.getSizeX()) || cy >= int(g.getSizeY())) continue;
    if (g.getCell(cx, cy) > 0.1f) ++occupied;
    g.setCell(cx, cy, 0.0f);
  }
  set_likelihood(g, a);
  save_grid(g, need(a, "out"));
  std::printf("hits: %zu readings under %.1f m, %zu occupied cells\nshift 0 0\n", hits.size(),
              max_range, occupied);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2)
    die("usage: mrpt_peer_tools rawlog|grid-yaml|grid-hits --option value ... (see the source)", 2);
  const std::string cmd = argv[1];
  try {
    const auto a = parse(argc, argv, 2);
    if (cmd == "rawlog") return cmd_rawlog(a);
    if (cmd == "grid-yaml") return cmd_grid_yaml(a);
    if (cmd == "grid-hits") return cmd_grid_hits(a);
  } catch (const std::exception& e) {
    die(std::string("MRPT: ") + e.what());
  }
  die("unknown subcommand '" + cmd + "'", 2);
}
