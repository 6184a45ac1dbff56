// The `structloc map` subcommands (build, grid, import --grid, import --dxf,
// export, check), one file each; options start at argv[3].
#pragma once

#include "subcommands.hpp"

namespace structloc::cli {

int MapBuildCommand(const Invocation& invocation);
int MapGridCommand(const Invocation& invocation);
int MapImportGridCommand(const Invocation& invocation);
int MapImportDxfCommand(const Invocation& invocation);
int MapExportCommand(const Invocation& invocation);
int MapCheckCommand(const Invocation& invocation);

}  // namespace structloc::cli
