// read_file(): a whole input file in memory, or an error naming it.
#pragma once

#include <string>

#include <cutroute/core/result.hpp>

namespace cutroute {

// The file's bytes. A directory, a file that cannot be opened (with the system's reason) or a read
// error is an error naming `path`. Lives in core so that every module reading its inputs (G-code,
// dialects, instances, machining problems) needs no other module for it.
Result<std::string> read_file(const std::string& path);

}  // namespace cutroute
