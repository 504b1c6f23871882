// cutroute machining: not yet implemented (placeholder until its issue lands).
#include <iostream>

#include "commands.hpp"

namespace cutroute::cli {

void add_machining(CLI::App& root, Commands& out) {
  auto* app = root.add_subcommand("machining", "(not yet implemented)");
  out.push_back({app, [] {
    std::cerr << "cutroute: error: 'machining' is not implemented yet\n";
    return kUsageError;
  }});
}

}  // namespace cutroute::cli
