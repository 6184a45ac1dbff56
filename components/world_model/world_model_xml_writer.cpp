// World model XML writer: the output of the map builders and importers, read
// back by LoadWorldModel (see world_model_xml.hpp).
#include <cmath>
#include <iomanip>
#include <sstream>

#include "structloc/world_model/world_model_xml.hpp"

namespace structloc::world_model {
namespace {

// XML comments may not contain "--"; attribute values must escape markup.
std::string CommentSafe(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '-' && !out.empty() && out.back() == '-') out += ' ';
    out += c;
  }
  return out;
}

std::string AttributeSafe(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

}  // namespace

double AsWritten(double metres) {
  return std::round(metres * 1e4) / 1e4;
}

void WriteWorldModel(const WorldModel& world, const std::vector<std::string>& comment_lines,
                     std::ostream& out) {
  std::ostringstream xml;
  xml << std::fixed << std::setprecision(4);  // AsWritten's 0.1 mm
  xml << "<?xml version=\"1.0\"?>\n";
  if (!comment_lines.empty()) {
    xml << "<!--\n";
    for (const auto& line : comment_lines) xml << "  " << CommentSafe(line) << "\n";
    xml << "-->\n";
  }
  xml << "<world name=\"" << AttributeSafe(world.Name()) << "\">\n";
  for (const auto& w : world.Walls()) {
    xml << "  <wall id=\"" << w.id << "\" x1=\"" << w.a.x() << "\" y1=\"" << w.a.y() << "\" x2=\""
        << w.b.x() << "\" y2=\"" << w.b.y() << "\"/>\n";
  }
  for (const auto& c : world.Corners()) {
    if (c.derived) continue;  // derived again from the wall ends on reading
    xml << "  <corner id=\"" << c.id << "\" x=\"" << c.position.x() << "\" y=\"" << c.position.y()
        << "\"/>\n";
  }
  for (const auto& c : world.Cylinders()) {
    xml << "  <cylinder id=\"" << c.id << "\" x=\"" << c.centre.x() << "\" y=\"" << c.centre.y()
        << "\" radius=\"" << c.radius << "\"/>\n";
  }
  xml << "</world>\n";
  out << xml.str();
}

}  // namespace structloc::world_model
