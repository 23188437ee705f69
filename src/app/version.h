#pragma once

namespace impactfe {

/// The project version (CMakeLists.txt) and the commit the program was built from
/// (`git describe --always --dirty`; "unknown" outside a git checkout). Written at build time
/// by cmake/write_version.cmake.
const char* program_version();
const char* program_commit();

}  // namespace impactfe
