// Small file helpers for tests that run the CLI: fresh temporary folders, files read whole.
#pragma once

#include <filesystem>
#include <string>

namespace cutroute::test {

// <temp>/cutroute-<name>-<pid>, emptied and created.
std::filesystem::path fresh_temp_dir(const std::string& name);

// An empty folder <temp>/cutroute-<prefix>-<name>-<pid>, removed first if it exists.
std::filesystem::path fresh_temp_dir(const std::string& prefix, const std::string& name);

// The file's bytes; empty when it cannot be read.
std::string read_text(const std::filesystem::path& path);

}  // namespace cutroute::test
