// map_server grid files: the YAML read with yaml-cpp, the image with OpenCV,
// values as map_server and Nav2's map_io compute them (see header).
#include "structloc/map_formats/grid_map_file.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <set>
#include <sstream>

#include "structloc/config/output_file.hpp"
#include "structloc/config/strict_number.hpp"
#include "structloc/config/strict_xml.hpp"

namespace structloc::map_formats {
namespace {

using config::ConfigError;

struct GridYaml {
  std::string image_path;  // resolved against the YAML's folder
  double resolution_m = 0.0;
  Eigen::Vector3d origin{0, 0, 0};
  bool negate = false;
  double occupied_thresh = 0.65;
  double free_thresh = 0.196;
  GridMapMode mode = GridMapMode::kTrinary;
};

const std::set<std::string> kKnownKeys = {"image",           "resolution",  "origin", "negate",
                                          "occupied_thresh", "free_thresh", "mode"};

std::string KnownKeyList() {
  std::string list;
  for (const auto& k : kKnownKeys) list += (list.empty() ? "" : ", ") + k;
  return list;
}

[[noreturn]] void Fail(const std::string& path, const YAML::Node& node, const std::string& what) {
  const auto mark = node.Mark();
  std::string where = path;
  if (!mark.is_null()) where += ":" + std::to_string(mark.line + 1);
  throw ConfigError(where + ": " + what);
}

double Number(const std::string& path, const YAML::Node& node, const std::string& key) {
  if (!node.IsScalar()) Fail(path, node, "'" + key + "' must be a number");
  const auto value = config::ParseFiniteDouble(node.Scalar());
  if (!value) Fail(path, node, "'" + key + "' is not a number: '" + node.Scalar() + "'");
  return *value;
}

double Threshold(const std::string& path, const YAML::Node& node, const std::string& key) {
  const double value = Number(path, node, key);
  if (value < 0.0 || value > 1.0)
    Fail(path, node,
         "'" + key + "' must lie in [0, 1] (an occupancy probability), not " + node.Scalar());
  return value;
}

GridYaml ReadYaml(const std::string& path, const GridMapReadOptions& options) {
  if (!std::filesystem::is_regular_file(path))
    throw ConfigError(path + ": no such grid map file (a map_server YAML)");
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    throw ConfigError(path + ":" + std::to_string(e.mark.line + 1) +
                      ": not a readable YAML file: " + e.msg);
  }
  if (!root.IsMap())
    throw ConfigError(path +
                      ": not a map_server YAML (expected keys such as image, resolution, "
                      "origin)");
  GridYaml yaml;
  std::set<std::string> seen;
  for (const auto& entry : root) {
    const std::string key = entry.first.IsScalar() ? entry.first.Scalar() : std::string("?");
    const YAML::Node& value = entry.second;
    if (!seen.insert(key).second) Fail(path, entry.first, "key '" + key + "' given twice");
    if (key == "image") {
      if (!value.IsScalar() || value.Scalar().empty())
        Fail(path, value, "'image' must name the PGM or PNG file");
      std::filesystem::path image(value.Scalar());
      if (image.is_relative()) image = std::filesystem::path(path).parent_path() / image;
      yaml.image_path = image.string();
    } else if (key == "resolution") {
      yaml.resolution_m = Number(path, value, key);
      if (!(yaml.resolution_m > 0.0))
        Fail(path, value, "'resolution' (metres per cell) must be positive, not " + value.Scalar());
    } else if (key == "origin") {
      if (!value.IsSequence() || value.size() != 3)
        Fail(path, value, "'origin' must be [x, y, yaw] (metres, metres, radians)");
      for (int i = 0; i < 3; ++i)
        yaml.origin[i] = Number(path, value[static_cast<size_t>(i)], "origin");
    } else if (key == "negate") {
      const std::string text = value.IsScalar() ? value.Scalar() : std::string();
      if (text == "0" || text == "false") {
        yaml.negate = false;
      } else if (text == "1" || text == "true") {
        yaml.negate = true;
      } else {
        Fail(path, value, "'negate' must be 0 or 1");
      }
    } else if (key == "occupied_thresh") {
      yaml.occupied_thresh = Threshold(path, value, key);
    } else if (key == "free_thresh") {
      yaml.free_thresh = Threshold(path, value, key);
    } else if (key == "mode") {
      const std::string text = value.IsScalar() ? value.Scalar() : std::string();
      if (text == "trinary") {
        yaml.mode = GridMapMode::kTrinary;
      } else if (text == "scale") {
        yaml.mode = GridMapMode::kScale;
      } else if (text == "raw") {
        yaml.mode = GridMapMode::kRaw;
      } else {
        Fail(path, value, "unknown 'mode' '" + text + "' (trinary, scale or raw)");
      }
    } else if (!options.ignore_unknown_keys) {
      Fail(path, entry.first,
           "unknown key '" + key + "' (known: " + KnownKeyList() +
               "; ROS ignores other keys: say so with the option to ignore unknown keys)");
    }
  }
  for (const char* required : {"image", "resolution", "origin"}) {
    if (seen.count(required) == 0)
      throw ConfigError(path + ": missing key '" + required +
                        "' (required: image, resolution, "
                        "origin)");
  }
  if (!(yaml.free_thresh < yaml.occupied_thresh)) {
    std::ostringstream what;
    what << path << ": free_thresh (" << yaml.free_thresh << ") must be below occupied_thresh ("
         << yaml.occupied_thresh << ")";
    throw ConfigError(what.str());
  }
  return yaml;
}

// What a PGM or PNG header says: the size, so that a huge image is refused
// before it is decoded, and for a PGM its largest grey value (maxval).
struct ImageHeader {
  uint64_t width = 0;
  uint64_t height = 0;
  uint64_t pgm_maxval = 0;  // 0: not a PGM
  bool pgm_ascii = false;   // P2 rather than P5
};

// The header of a PGM or PNG; nullopt for other formats (refused: their size
// is not known before OpenCV decodes them whole).
std::optional<ImageHeader> ReadImageHeader(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::array<unsigned char, 24> head{};
  in.read(reinterpret_cast<char*>(head.data()), static_cast<std::streamsize>(head.size()));
  const auto got = static_cast<size_t>(in.gcount());
  static const std::array<unsigned char, 8> kPng = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (got >= 24 && std::equal(kPng.begin(), kPng.end(), head.begin())) {
    auto be32 = [&](size_t at) {
      return (uint64_t{head[at]} << 24) | (uint64_t{head[at + 1]} << 16) |
             (uint64_t{head[at + 2]} << 8) | uint64_t{head[at + 3]};
    };
    ImageHeader header;
    header.width = be32(16);
    header.height = be32(20);
    return header;
  }
  if (got >= 2 && head[0] == 'P' && (head[1] == '2' || head[1] == '5')) {
    in.clear();
    in.seekg(2);
    std::array<uint64_t, 3> fields{};  // width, height, maxval
    for (auto& value : fields) {
      for (int c = in.peek(); c == '#' || std::isspace(c); c = in.peek()) {
        if (c == '#') {
          std::string comment;
          std::getline(in, comment);
        } else {
          in.get();
        }
      }
      if (!(in >> value)) return std::nullopt;
    }
    ImageHeader header;
    header.width = fields[0];
    header.height = fields[1];
    header.pgm_maxval = fields[2];
    header.pgm_ascii = head[1] == '2';
    return header;
  }
  return std::nullopt;
}

std::string SizeText(uint64_t width, uint64_t height) {
  return std::to_string(width) + " x " + std::to_string(height);
}

cv::Mat ReadImage(const std::string& yaml_path, const std::string& image_path,
                  const GridMapReadOptions& options) {
  if (!std::filesystem::is_regular_file(image_path))
    throw ConfigError(yaml_path + ": the image it names, " + image_path + ", does not exist");
  const std::string too_large = yaml_path + ": the image " + image_path + " is too large: ";
  const std::string limit = " cells (the limit is " + std::to_string(options.max_cells) + ")";
  const auto header = ReadImageHeader(image_path);
  if (!header)
    throw ConfigError(yaml_path + ": the image " + image_path +
                      " is neither a PNG nor a PGM (map_server's formats, whose size is read "
                      "before decoding); convert it to PNG");
  // Each side first: a PGM header's numbers may be large enough for their
  // product to wrap around.
  if (header->width > options.max_cells || header->height > options.max_cells ||
      header->width * header->height > options.max_cells)
    throw ConfigError(too_large + SizeText(header->width, header->height) + limit);
  cv::Mat image;
  try {
    image = cv::imread(image_path, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {
    throw ConfigError(yaml_path + ": cannot read the image " + image_path + ": " + e.what());
  }
  if (image.empty())
    throw ConfigError(yaml_path + ": cannot read the image " + image_path +
                      " (not a PGM, PNG or other image OpenCV reads, or empty)");
  if (static_cast<uint64_t>(image.cols) * static_cast<uint64_t>(image.rows) > options.max_cells)
    throw ConfigError(
        too_large + SizeText(static_cast<uint64_t>(image.cols), static_cast<uint64_t>(image.rows)) +
        limit);
  if (image.depth() != CV_8U && image.depth() != CV_16U)
    throw ConfigError(yaml_path + ": the image " + image_path +
                      " has neither 8 nor 16 bits per channel");
  // Grey levels to 0..255 as map_server reads them: white is a PGM's maxval
  // (OpenCV scales only ASCII PGMs of up to 8 bits itself), a 16-bit PNG's 65535.
  double full = image.depth() == CV_16U ? 65535.0 : 255.0;
  if (header->pgm_maxval > 0 && !(header->pgm_ascii && image.depth() == CV_8U))
    full = static_cast<double>(header->pgm_maxval);
  if (!(full >= 1.0 && full <= 65535.0))
    throw ConfigError(yaml_path + ": the image " + image_path + " has a maxval of " +
                      std::to_string(header->pgm_maxval) + " (PGM allows 1..65535)");
  if (image.depth() != CV_8U || full != 255.0) {
    cv::Mat eight;
    image.convertTo(eight, CV_8U, 255.0 / full);
    image = eight;
  }
  return image;
}

int8_t CellValue(const GridYaml& yaml, int grey, int alpha, const std::string& yaml_path) {
  if (yaml.mode == GridMapMode::kRaw) {
    if (grey == 255) return OccupancyGrid::kUnknown;
    if (grey > 100)
      throw ConfigError(yaml_path +
                        ": mode raw holds cell values 0..100 and 255 (unknown), but "
                        "the image has the grey level " +
                        std::to_string(grey));
    return static_cast<int8_t>(grey);
  }
  const double p = yaml.negate ? grey / 255.0 : (255.0 - grey) / 255.0;
  if (yaml.mode == GridMapMode::kScale && alpha < 255) return OccupancyGrid::kUnknown;
  if (p > yaml.occupied_thresh) return OccupancyGrid::kOccupied;
  if (p < yaml.free_thresh) return OccupancyGrid::kFree;
  if (yaml.mode == GridMapMode::kTrinary) return OccupancyGrid::kUnknown;
  return static_cast<int8_t>(
      std::lround(99.0 * (p - yaml.free_thresh) / (yaml.occupied_thresh - yaml.free_thresh)));
}

std::string NumberText(double value) {
  std::ostringstream out;
  out.precision(12);
  out << value;
  return out.str();
}

}  // namespace

OccupancyGrid LoadGridMap(const std::string& yaml_path, const GridMapReadOptions& options,
                          GridMapSource* source) {
  const GridYaml yaml = ReadYaml(yaml_path, options);
  if (source != nullptr) *source = {yaml.mode, yaml.image_path};
  const cv::Mat image = ReadImage(yaml_path, yaml.image_path, options);
  OccupancyGrid grid(image.cols, image.rows, yaml.resolution_m, yaml.origin);
  const int channels = image.channels();
  const int colour = channels >= 3 ? 3 : 1;  // grey+alpha has one grey channel
  const bool has_alpha = channels == 2 || channels == 4;
  // The value of an opaque pixel by its grey level, each found on first use
  // (raw mode refuses some levels, only when the image holds them).
  constexpr int kNotYet = INT_MIN;
  std::array<int, 256> opaque;
  opaque.fill(kNotYet);
  for (int y = 0; y < image.rows; ++y) {
    const uint8_t* row = image.ptr<uint8_t>(y);
    for (int x = 0; x < image.cols; ++x) {
      const uint8_t* px = row + static_cast<ptrdiff_t>(x) * channels;
      int sum = 0;
      for (int c = 0; c < colour; ++c) sum += px[c];
      const int grey = (sum + colour / 2) / colour;
      const int alpha = has_alpha ? px[channels - 1] : 255;
      int8_t value;
      if (alpha == 255) {
        int& known = opaque[static_cast<size_t>(grey)];
        if (known == kNotYet) known = CellValue(yaml, grey, alpha, yaml_path);
        value = static_cast<int8_t>(known);
      } else {
        value = CellValue(yaml, grey, alpha, yaml_path);
      }
      // Image row 0 is the top of the map; grid row 0 the bottom.
      grid.At(x, image.rows - 1 - y) = value;
    }
  }
  return grid;
}

void SaveGridMap(const OccupancyGrid& grid, const std::string& yaml_path,
                 const std::vector<std::string>& inputs) {
  if (grid.width <= 0 || grid.height <= 0 ||
      grid.cells.size() != static_cast<size_t>(grid.width) * static_cast<size_t>(grid.height))
    throw std::invalid_argument("SaveGridMap: the grid is empty or its cells do not match " +
                                SizeText(static_cast<uint64_t>(std::max(grid.width, 0)),
                                         static_cast<uint64_t>(std::max(grid.height, 0))));
  const std::filesystem::path yaml_file(yaml_path);
  std::filesystem::path image_file = yaml_file;
  image_file.replace_extension(".pgm");
  if (image_file == yaml_file)
    throw ConfigError(yaml_path + ": the grid YAML must not end in .pgm (the image goes there)");
  cv::Mat image(grid.height, grid.width, CV_8UC1);
  for (int row = 0; row < grid.height; ++row) {
    uint8_t* out = image.ptr<uint8_t>(grid.height - 1 - row);
    for (int column = 0; column < grid.width; ++column) {
      const int value = grid.At(column, row);
      out[column] = value >= 65 ? 0 : (value >= 0 && value <= 19 ? 254 : 205);
    }
  }
  std::vector<uint8_t> encoded;
  if (!cv::imencode(".pgm", image, encoded, {cv::IMWRITE_PXM_BINARY, 1}))
    throw std::runtime_error(image_file.string() + ": OpenCV could not encode the PGM");

  std::vector<std::string> forbidden = inputs;
  forbidden.push_back(yaml_path);
  config::OutputFile image_out(image_file.string(), forbidden);
  config::OutputFile yaml_out(yaml_path, inputs);
  image_out.Stream().write(reinterpret_cast<const char*>(encoded.data()),
                           static_cast<std::streamsize>(encoded.size()));
  YAML::Emitter emitter;
  emitter << YAML::BeginMap;
  emitter << YAML::Key << "image" << YAML::Value << image_file.filename().string();
  emitter << YAML::Key << "mode" << YAML::Value << "trinary";
  emitter << YAML::Key << "resolution" << YAML::Value << NumberText(grid.resolution_m);
  emitter << YAML::Key << "origin" << YAML::Value << YAML::Flow << YAML::BeginSeq
          << NumberText(grid.origin.x()) << NumberText(grid.origin.y())
          << NumberText(grid.origin.z()) << YAML::EndSeq;
  emitter << YAML::Key << "negate" << YAML::Value << 0;
  emitter << YAML::Key << "occupied_thresh" << YAML::Value << "0.65";
  emitter << YAML::Key << "free_thresh" << YAML::Value << "0.196";
  emitter << YAML::EndMap;
  yaml_out.Stream() << emitter.c_str() << "\n";
  image_out.Flush();
  yaml_out.Flush();
  image_out.Commit();
  yaml_out.Commit();
}

}  // namespace structloc::map_formats
