// read_file(): a whole input file in memory, or an error naming it.
#pragma once

#include <cstdint>
#include <string>

#include <cutroute/core/result.hpp>

namespace cutroute {

// The most any input is read into memory [bytes]: a drawing, a program or an instance beyond it is
// refused rather than exhausting the machine (and an endless input such as /dev/zero ends there).
inline constexpr std::uintmax_t kMaxInputBytes = 512ull << 20;

// The file's bytes. A directory, a file that cannot be opened (with the system's reason), a read
// error or more than `max_bytes` is an error naming `path`; a pipe or FIFO is read to its end.
// Lives in core so that every module reading its inputs (G-code, drawings, dialects, instances,
// machining problems) needs no other module for it.
Result<std::string> read_file(const std::string& path, std::uintmax_t max_bytes = kMaxInputBytes);

}  // namespace cutroute
