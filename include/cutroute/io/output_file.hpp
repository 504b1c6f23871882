// write_file_atomic(): outputs go to a temporary file that is renamed over the target when complete.
#pragma once

#include <string>
#include <string_view>

#include <cutroute/core/result.hpp>

namespace cutroute::io {

// Writes content to "<path>.tmp-<pid>" in the same folder, flushes, then renames it to path,
// so a failed or interrupted run never leaves a half-written program behind. "-" writes to stdout.
Status write_file_atomic(const std::string& path, std::string_view content);

// Reads a whole file; the error names the file.
Result<std::string> read_file(const std::string& path);

}  // namespace cutroute::io
