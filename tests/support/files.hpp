// Small file helpers for tests: read a whole file, make a fresh temporary folder.
#pragma once

#include <filesystem>
#include <string>

namespace cutroute::test {

// The whole file as bytes ("" when it cannot be read).
std::string slurp(const std::filesystem::path& p);

// An empty folder <temp>/cutroute-<prefix>-<name>-<pid>, removed first if it exists.
std::filesystem::path fresh_temp_dir(const std::string& prefix, const std::string& name);

}  // namespace cutroute::test
