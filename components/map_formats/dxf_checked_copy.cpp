// A DXF drawing copied as dxflib reads it (see header).
#include "dxf_checked_copy.hpp"

#include <dxflib/dl_dxf.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <ostream>

#include "structloc/config/strict_xml.hpp"

namespace structloc::map_formats {
namespace {

// Most vertices, knots or points one entity may announce: dxflib allocates
// what the count says before reading any (a 300-byte file announcing 2e7
// LWPOLYLINE vertices took 680 MB); a floor plan needs far fewer.
constexpr long long kMaxAnnouncedCount = 1'000'000;

// The group codes by which an entity announces how many items dxflib is to
// allocate for: LWPOLYLINE's vertices, SPLINE's knots, control and fit points,
// LEADER's vertices.
bool IsAnnouncedCount(const std::string& kind, unsigned int code) {
  return (kind == "LWPOLYLINE" && code == 90) ||
         (kind == "SPLINE" && (code == 72 || code == 73 || code == 74)) ||
         (kind == "LEADER" && code == 76);
}

// The longest line dxflib reads whole: it reads with fgets into a buffer of
// DL_DXF_MAXLINE (1024) bytes, so a line of 1023 bytes or more (its '\r' if
// any counted) is read as two, and every code and value after it pairs
// differently from how this file pairs them.
constexpr size_t kMaxLineBytes = DL_DXF_MAXLINE - 2;

// A line as dxflib reads it: up to its first NUL (it handles C strings), its
// trailing CR and LF dropped. A line that starts with NUL leaves dxflib's
// text as it was (`before`): it keeps the group code or value it read last,
// so "10 / 0.0 / NUL / x / 90 / 4000001010" inside a LWPOLYLINE announces
// 4e9 vertices to dxflib although a NUL line looks like group 0 here.
std::string AsDxflibReadsIt(const std::string& line, const std::string& before) {
  if (!line.empty() && line[0] == '\0') return before;
  std::string text = line.substr(0, line.find('\0'));
  while (!text.empty() && (text.back() == '\r' || text.back() == '\n')) text.pop_back();
  return text;
}

// An entity's name without blanks around it: dxflib keeps a value's blanks
// in some versions and strips them in others; the guard takes the name that
// checks more entities.
std::string Unblanked(const std::string& text) {
  const size_t first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

// Writes the drawing to `copy` as dxflib reads it, refusing, with the line,
// counts beyond kMaxAnnouncedCount in all (dxflib allocates and zeroes for a
// count as soon as it reads it, then frees at the entity's end: a thousand
// entities announcing a million each would zero 32 GB; a count past 536
// million overflows inside dxflib, which then frees its buffer twice), and
// lines dxflib would split. Group codes and values alternate line by line; a
// group 0 or 9 starts an object.
void CopyChecked(const std::string& path, std::ostream& copy) {
  std::ifstream in(path, std::ios::binary);
  std::string code_line, value_line, code_text, value;
  std::string kind;
  long long announced = 0;
  const auto check_length = [&](const std::string& text, size_t line) {
    if (text.size() <= kMaxLineBytes) return;
    throw config::ConfigError(path + ":" + std::to_string(line) + ": a line of " +
                              std::to_string(text.size()) + " bytes; DXF readers take at most " +
                              std::to_string(kMaxLineBytes) + " (is it a DXF drawing?)");
  };
  for (size_t line = 1; std::getline(in, code_line) && std::getline(in, value_line); line += 2) {
    check_length(code_line, line);
    check_length(value_line, line + 1);
    // As dxflib reads a group code: strtol's long cut to an int (its toInt),
    // so that 4294967386 is 90; a line that is no number (even an empty one)
    // is code 0.
    code_text = AsDxflibReadsIt(code_line, code_text);
    const int code = static_cast<int>(std::strtol(code_text.c_str(), nullptr, 10));
    value = AsDxflibReadsIt(value_line, value);
    copy << code << '\n' << value << '\n';
    if (code < 0) continue;  // dxflib judges the rest
    // dxflib starts an object at a group 9 as at a group 0: a header
    // variable's name, but "9 / LWPOLYLINE" starts a polyline (found by the
    // fuzzer: a count past the guard, whose allocation overflowed inside
    // dxflib and freed its vertex buffer twice).
    if (code == 0 || code == 9) {
      kind = Unblanked(value);
      continue;
    }
    if (!IsAnnouncedCount(kind, static_cast<unsigned int>(code))) continue;
    const long long count = std::strtoll(value.c_str(), nullptr, 10);
    if (count >= 0 && count <= kMaxAnnouncedCount - announced) {
      announced += count;
      continue;
    }
    throw config::ConfigError(path + ":" + std::to_string(line + 1) + ": a " + kind +
                              " announces " + std::to_string(count) + " items (group code " +
                              std::to_string(code) + "), making more than " +
                              std::to_string(kMaxAnnouncedCount) +
                              " vertices, knots or points in all (or negative): no floor plan");
  }
}

}  // namespace

DxfCheckedCopy::DxfCheckedCopy(const std::string& path) {
  std::string name = (std::filesystem::temp_directory_path() / "structloc-dxf.XXXXXX").string();
  const int fd = mkstemp(name.data());
  if (fd < 0) {
    throw config::ConfigError(path + ": no temporary file for the checked copy of the drawing in " +
                              std::filesystem::temp_directory_path().string() +
                              " (set TMPDIR to a writable folder)");
  }
  close(fd);
  copy_ = name;
  try {
    std::ofstream out(copy_, std::ios::binary | std::ios::trunc);
    CopyChecked(path, out);
    out.close();
    if (!out) {
      throw config::ConfigError(path + ": could not write its checked copy to " + copy_ +
                                " (is the temporary folder full?)");
    }
  } catch (...) {
    std::remove(copy_.c_str());
    throw;
  }
}

DxfCheckedCopy::~DxfCheckedCopy() {
  std::remove(copy_.c_str());
}

}  // namespace structloc::map_formats
