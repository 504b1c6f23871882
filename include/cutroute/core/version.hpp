// The library's version string.
#pragma once

namespace cutroute {
const char* version();
// Absolute path of the bundled data/ folder (materials, dialects, examples); the environment
// variable CUTROUTE_DATA_DIR overrides the path compiled in.
const char* data_dir();
}  // namespace cutroute
