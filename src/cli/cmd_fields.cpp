// hgrid fields: the table of a measurement's fields (measure/fields.hpp).
#include <cstdio>
#include <memory>

#include "common.hpp"
#include "hgridlab/measure/fields.hpp"

namespace hgrid::cli {

void register_fields_commands(CLI::App& app) {
  {
    auto md = std::make_shared<bool>(false);
    auto* sub = app.add_subcommand("fields", "the fields of a measurement (count --json, result files, Python's count)");
    sub->add_flag("--markdown", *md, "as a Markdown table (docs/MEASUREMENT.md)");
    sub->callback([md] {
      if (*md) std::printf("| field | unit | meaning |\n|---|---|---|\n");
      for (const MeasurementField& f : measurement_fields())
        std::printf(*md ? "| `%s` | %s | %s |\n" : "%-48s %-7s %s\n", f.name, *f.unit ? f.unit : "-", f.meaning);
    });
  }
}

}  // namespace hgrid::cli
