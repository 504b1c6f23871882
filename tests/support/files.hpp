// Small file helpers for tests that run the CLI: a fresh temporary folder, a file read whole.
#pragma once

#include <filesystem>
#include <string>

namespace cutroute::test {

// <temp>/cutroute-<name>-<pid>, emptied and created.
std::filesystem::path fresh_temp_dir(const std::string& name);

// The file's bytes; empty when it cannot be read.
std::string read_text(const std::filesystem::path& path);

}  // namespace cutroute::test
