// `hgrid modelfigs`: the data behind the paper's Figs. 2-10 (and 13).
#include <filesystem>
#include <iostream>
#include <memory>

#include "hgridlab/calibration/calibration.hpp"
#include "common.hpp"
#include "hgridlab/io/atomic_file.hpp"
#include "hgridlab/model/figures.hpp"

namespace hgrid::cli {

void register_modelfigs_commands(CLI::App& app) {
  auto f = std::make_shared<std::string>("results/model");
  auto only = std::make_shared<std::string>();
  auto* figs = app.add_subcommand("modelfigs", "Write the data of the paper's Figs. 2-10 (and 13) as CSV");
  figs->add_option("--out", *f, "output directory")->capture_default_str();
  figs->add_option("--only", *only, "comma-separated figure numbers, e.g. 4,9 (default: all)");
  auto time_model = std::make_shared<std::string>();
  figs->add_option("--time-model", *time_model,
                   "a calibration file (e.g. results/calibration.json) whose 3D time model adds the time-optimal "
                   "sizes to Fig. 13");
  figs->callback([f, only, time_model] {
    std::optional<TimeCoefficients> time;
    if (!time_model->empty()) {
      const Calibration c = load_calibration(*time_model);
      if (!c.time_model(3))
        throw InputError("time-model", "'" + *time_model + "' has no 3D time model (run `hgrid calibrate`)");
      time = c.time_model(3)->coef;
    }
    std::filesystem::create_directories(*f);
    write_model_figures([&](const std::string& name, const std::string& csv) { write_text_atomically(*f + "/" + name, csv); },
                        *only, std::cerr, time);
  });
}

}  // namespace hgrid::cli
