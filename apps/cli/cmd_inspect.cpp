// cutroute inspect: not yet implemented (placeholder until its issue lands).
#include <iostream>

#include "commands.hpp"

namespace cutroute::cli {

void add_inspect(CLI::App& root, Commands& out) {
  auto* app = root.add_subcommand("inspect", "(not yet implemented)");
  out.push_back({app, [] {
    std::cerr << "cutroute: error: 'inspect' is not implemented yet\n";
    return kUsageError;
  }});
}

}  // namespace cutroute::cli
