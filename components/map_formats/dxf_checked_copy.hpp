// A DXF drawing copied as dxflib reads it and checked on the way, for dxflib
// to read the copy: dxflib allocates for the counts an entity announces
// before it reads any item, and its reading has quirks (a line cut at a NUL
// or at 1023 bytes, an empty code line read as group 0, a code cut to an
// int); a check of the original that reads it otherwise lets a count past.
// The copy has one group code (the number dxflib makes of it) and one value
// per line, so that what dxflib reads is what was checked. Private to
// map_formats.
#pragma once

#include <string>

namespace structloc::map_formats {

class DxfCheckedCopy {
 public:
  // Reads `path` and writes the copy into a new file of the temporary
  // folder; throws config::ConfigError, naming the file and line, for a
  // line dxflib would split or counts beyond a million vertices, knots or
  // points in all.
  explicit DxfCheckedCopy(const std::string& path);
  ~DxfCheckedCopy();  // removes the copy
  DxfCheckedCopy(const DxfCheckedCopy&) = delete;
  DxfCheckedCopy& operator=(const DxfCheckedCopy&) = delete;

  const std::string& Path() const { return copy_; }

 private:
  std::string copy_;
};

}  // namespace structloc::map_formats
