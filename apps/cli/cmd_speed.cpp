// cutroute speed: not yet implemented (placeholder until its issue lands).
#include <iostream>

#include "commands.hpp"

namespace cutroute::cli {

void add_speed(CLI::App& root, Commands& out) {
  auto* app = root.add_subcommand("speed", "(not yet implemented)");
  out.push_back({app, [] {
    std::cerr << "cutroute: error: 'speed' is not implemented yet\n";
    return kUsageError;
  }});
}

}  // namespace cutroute::cli
