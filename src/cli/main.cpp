// hgrid: the command-line front end of hgridlab.
#include <cstdio>
#include <exception>
#include <iostream>
#include <sstream>

#include "cli/common.hpp"
#include "grid/error.hpp"
#include "io/provenance.hpp"

namespace hgrid::cli {

std::vector<double> parse_list(const std::string& text, const std::string& field) {
  std::vector<double> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    std::size_t used = 0;
    double v = 0;
    try {
      v = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size())
      throw InputError(field, "'" + item + "' is not a number (expected a comma-separated list)");
    out.push_back(v);
  }
  if (out.empty()) throw InputError(field, "empty list");
  return out;
}

}  // namespace hgrid::cli

int main(int argc, char** argv) {
  CLI::App app{"hgrid: hierarchical-grid contact detection, counted, and its cost model\n"
               "(Krijgsman, Ogarko & Luding, Comp. Part. Mech. 1 (2014) 357-372)"};
  app.set_version_flag("--version", std::string("hgrid ") + hgrid::version() + " (" + hgrid::git_hash() + ", " +
                                        hgrid::compiler_id() + ")");
  app.require_subcommand(1);
  app.fallthrough(false);
  hgrid::cli::register_grid_commands(app);
  hgrid::cli::register_model_commands(app);
  hgrid::cli::register_generate_commands(app);
  hgrid::cli::register_run_commands(app);
  hgrid::cli::register_export_commands(app);
  hgrid::cli::register_calibrate_commands(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "hgrid: " << e.what() << " (see --help)\n";
    return hgrid::cli::kBadInput;
  } catch (const hgrid::InputError& e) {
    std::cerr << "hgrid: error: " << e.what() << "\n";
    return hgrid::cli::kBadInput;
  } catch (const std::exception& e) {
    std::cerr << "hgrid: internal error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
