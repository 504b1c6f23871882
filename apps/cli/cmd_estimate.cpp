// cutroute estimate: not yet implemented (placeholder until its issue lands).
#include <iostream>

#include "commands.hpp"

namespace cutroute::cli {

void add_estimate(CLI::App& root, Commands& out) {
  auto* app = root.add_subcommand("estimate", "(not yet implemented)");
  out.push_back({app, [] {
    std::cerr << "cutroute: error: 'estimate' is not implemented yet\n";
    return kUsageError;
  }});
}

}  // namespace cutroute::cli
