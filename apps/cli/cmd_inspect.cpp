// cutroute inspect: read a nest and report what it holds (JSON summary, SVG picture).
#include <iostream>

#include <nlohmann/json.hpp>

#include <cutroute/io/nest_loader.hpp>
#include <cutroute/io/nest_svg.hpp>
#include <cutroute/io/output_file.hpp>
#include <cutroute/io/inspect_report.hpp>

#include "commands.hpp"
#include "input_options.hpp"

namespace cutroute::cli {

void add_inspect(CLI::App& root, Commands& out) {
  struct Opts {
    std::string nest;
    bool json = false;
    std::string svg;
    InputOptions input;
  };
  auto opts = std::make_shared<Opts>();
  auto* app = root.add_subcommand("inspect", "Read a DXF nest and report its contours, parts and holes");
  app->add_option("NEST", opts->nest, "DXF file")->required();
  app->add_flag("--json", opts->json, "Print one JSON object instead of the text summary");
  app->add_option("--svg", opts->svg, "Write a picture of the nest to this SVG file");
  add_input_options(app, opts->input);

  out.push_back({app, [opts]() -> int {
    auto load_options = to_load_options(opts->input);
    if (!load_options) {
      std::cerr << "cutroute: " << load_options.error().message << '\n';
      return kUsageError;
    }
    if (!opts->svg.empty() && io::same_output(opts->svg, opts->nest)) {
      std::cerr << "cutroute: error: the output " << opts->svg << " is the input drawing " << opts->nest
                << ": an output never replaces its input\n";
      return kUsageError;
    }
    auto loaded = io::load_nest(opts->nest, *load_options);
    if (!loaded) return fail(loaded.error());

    const nlohmann::json report = io::inspect_report(*loaded);
    if (opts->json) {
      std::cout << json_text(report) << '\n';
    } else {
      std::cout << io::inspect_text(report);
    }
    if (!opts->svg.empty()) {
      if (auto st = io::write_file_atomic(opts->svg, io::nest_to_svg(*loaded)); !st) return fail(st.error());
    }
    // Errors always; in the text form the warnings too (the JSON lists them), the first 20 of
    // them: the count alone ("2 warnings") left the reader to guess what the drawing holds.
    int errors = 0;
    std::size_t warnings = 0;
    for (const auto& d : loaded->diagnostics) {
      if (d.severity == Severity::error) {
        std::cerr << "cutroute: " << format(d) << '\n';
        ++errors;
      } else if (!opts->json && warnings++ < 20) {
        std::cerr << "cutroute: " << format(d) << '\n';
      }
    }
    if (!opts->json && warnings > 20)
      std::cerr << "cutroute: " << opts->nest << ": " << (warnings - 20) << " more warning(s): --json lists them all\n";
    return errors > 0 ? kInputError : kOk;
  }});
}

}  // namespace cutroute::cli
