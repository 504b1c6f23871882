// cutroute demo: write the bundled demo nest (generated, like the source paper's example sheet) as DXF.
#include <iostream>

#include <cutroute/io/dxf_writer.hpp>
#include <cutroute/io/output_file.hpp>
#include <cutroute/model/demo_nest.hpp>

#include "commands.hpp"

namespace cutroute::cli {

void add_demo(CLI::App& root, Commands& out) {
  auto path = std::make_shared<std::string>();
  auto* app = root.add_subcommand(
      "demo", "Write the demo nest: a 2000 x 1000 mm sheet with 14 parts and 21 contours, as a DXF file");
  app->add_option("OUT,-o,--output", *path, "DXF file to write (as the argument or after -o)")->required();
  out.push_back({app, [path]() -> int {
    std::vector<io::DxfWriteEntity> entities;
    for (auto& c : model::make_demo_sheet()) entities.push_back({std::move(c.contour), std::move(c.layer)});
    if (auto st = io::write_file_atomic(*path, io::write_dxf(entities, io::DxfWriteOptions{})); !st)
      return fail(st.error());
    return kOk;
  }});
}

}  // namespace cutroute::cli
