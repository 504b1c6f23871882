// write_file_atomic(): outputs go to a temporary file that is renamed over the target when complete.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <cutroute/core/result.hpp>

namespace cutroute::io {

// Writes content to "<path>.tmp-<pid>-<n>" in the same folder (n counts this process's
// outputs, so threads of a batch never share one), flushes, then renames it to path, so a failed
// or interrupted run never leaves a half-written program behind. "-" writes to stdout.
Status write_file_atomic(const std::string& path, std::string_view content);

struct OutputFile {
  std::string path;
  std::string content;
};

// The outputs of one job, all or none: each is written to its temporary file first, and only
// when every one is complete (and no target is a folder) are they renamed into place, in the
// order given (the program last). A run that fails to write one leaves none of them; a rename
// that fails after others succeeded (the folder vanished meanwhile) leaves the earlier ones. "-"
// is written to stdout after the others are in place.
Status write_files_atomic(const std::vector<OutputFile>& files);

// Reads a whole file; the error names the file.
Result<std::string> read_file(const std::string& path);

}  // namespace cutroute::io
