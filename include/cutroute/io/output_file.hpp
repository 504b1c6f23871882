// write_file_atomic(): outputs go to a temporary file that is renamed over the target when complete.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <cutroute/core/result.hpp>

namespace cutroute::io {

// Writes content to a temporary file in the same folder (".cutroute-<pid>-<n>.tmp", n counting
// this process's outputs, so threads of a batch never share one), flushes, then renames it to
// path, so a failed or interrupted run never leaves a half-written program behind. A symbolic
// link is followed (its target gets the content); a device, FIFO or socket is written in place,
// never replaced. "-" writes to stdout.
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

// Can an output be written there? The same checks and errors as write_files_atomic() (a folder,
// a missing or read-only folder: a temporary file is created and removed), made before a long
// run instead of after it. "-", devices and FIFOs pass.
Status check_output(const std::string& path);

// Do two paths name the same file ("-" only itself; "x.ngc", "./x.ngc", a symbolic or hard link
// to it: one file)? For outputs against each other and against the inputs.
bool same_output(const std::string& a, const std::string& b);

// Removes the temporary files of outputs being written at this moment, for a signal handler
// that ends the process (a second Ctrl-C during writing left .cutroute-<pid>-<n>.tmp files of
// tens of MB beside the outputs). Async-signal-safe: no allocation, no lock, only unlink().
void remove_temp_files() noexcept;

// For a signal handler about to end the process: true when an output set is being moved into
// place at this moment (write_files_atomic's renames). The signal `sig` is then raised again, with
// its default action, once every set under way is in place: a second Ctrl-C in between left a new
// program beside the old run's report. Async-signal-safe.
bool defer_signal_while_committing(int sig) noexcept;

// Holds off such a signal while it lives (write_files_atomic() takes one around its renames).
class CommitGuard {
 public:
  CommitGuard() noexcept;
  ~CommitGuard();
  CommitGuard(const CommitGuard&) = delete;
  CommitGuard& operator=(const CommitGuard&) = delete;
};

}  // namespace cutroute::io
