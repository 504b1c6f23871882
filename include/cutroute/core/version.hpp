// The library's version string.
#pragma once

namespace cutroute {
const char* version();
// Path of the bundled data/ folder (machines, materials, dialects, examples): the environment
// variable CUTROUTE_DATA_DIR, else data/ beside the executable or ../share/cutroute/data (a copied
// or installed binary), else the source tree's data/ compiled in.
const char* data_dir();
}  // namespace cutroute
