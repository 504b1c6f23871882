// Options shared by every subcommand that reads a nest: units, layers, snap, sheet size.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include <cutroute/core/result.hpp>
#include <cutroute/core/units.hpp>
#include <cutroute/io/nest_loader.hpp>

namespace cutroute::cli {

// A range check for a floating-point option that also refuses NaN and infinity (CLI::Range lets
// NaN through: every comparison with it is false).
CLI::Validator finite_range(double lo, double hi);

struct InputOptions {
  double snap_mm = tol::kSnapMm;
  double close_gaps_mm = tol::kCloseGapMm;
  std::string units;
  std::vector<std::string> layers;
  std::vector<std::string> ignore_layers;
  std::string sheet;  // "W,H" [mm]
};

void add_input_options(CLI::App* app, InputOptions& o);
// Turns parsed options into loader options; a malformed --sheet is a usage error (message only).
Result<io::NestLoadOptions> to_load_options(const InputOptions& o);

// "X,Y" in mm (--start of optimize and estimate); the message names the option `what`.
Result<geometry::Vec2> parse_point(const std::string& s, const char* what);

}  // namespace cutroute::cli
