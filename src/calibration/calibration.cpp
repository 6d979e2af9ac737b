#include "hgridlab/calibration/calibration.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <unistd.h>

#include "hgridlab/base/error.hpp"
#include "hgridlab/io/atomic_file.hpp"

namespace hgrid {
namespace {

constexpr const char* kFormat = "hgridlab-calibration-2";
constexpr const char* kFormatV1 = "hgridlab-calibration-1";  // K only, before the time model

const char* env(const char* name) {
  const char* v = std::getenv(name);
  return v && *v ? v : nullptr;
}

// The numeric fields of the record, in file order.
struct NumField {
  const char* key;
  double Calibration::*member;
};
constexpr NumField kNumbers[] = {
    {"K", &Calibration::K},           {"K_err", &Calibration::K_err},
    {"c_cell", &Calibration::c_cell}, {"c_cell_err", &Calibration::c_cell_err},
    {"c_test", &Calibration::c_test}, {"c_test_err", &Calibration::c_test_err},
    {"c0", &Calibration::c0},         {"c0_err", &Calibration::c0_err},
    {"cov_cell_test", &Calibration::cov_cell_test}, {"r2", &Calibration::r2},
    {"rms_rel_residual", &Calibration::rms_rel_residual},
};

nlohmann::ordered_json quality_json(const FitQuality& q) {
  return {{"r2_log", q.r2_log}, {"rms_rel_residual", q.rms_rel}, {"max_rel_residual", q.max_rel}, {"points", q.points}};
}

FitQuality quality_from(const nlohmann::json& j) {
  FitQuality q;
  q.r2_log = j.at("r2_log").get<double>();
  q.rms_rel = j.at("rms_rel_residual").get<double>();
  q.max_rel = j.at("max_rel_residual").get<double>();
  q.points = j.at("points").get<int>();
  return q;
}

template <std::size_t N>
nlohmann::ordered_json terms_json(const std::array<std::string_view, N>& names, const std::array<double, N>& coef,
                                  const std::array<double, N>& err) {
  nlohmann::ordered_json j;
  for (std::size_t k = 0; k < N; ++k) j[std::string(names[k])] = {{"seconds", coef[k]}, {"err", err[k]}};
  return j;
}

template <std::size_t N>
void terms_from(const nlohmann::json& j, const std::array<std::string_view, N>& names, std::array<double, N>& coef,
                std::array<double, N>& err) {
  for (std::size_t k = 0; k < N; ++k) {
    const auto& t = j.at(std::string(names[k]));
    coef[k] = t.at("seconds").get<double>();
    err[k] = t.at("err").get<double>();
    if (!(std::isfinite(coef[k]) && coef[k] >= 0)) throw std::invalid_argument(std::string(names[k]) + " < 0");
  }
}

nlohmann::ordered_json time_json(const TimeModelFit& t) {
  nlohmann::ordered_json j;
  j["model"] = "seconds = sum over terms of (seconds per unit) x (count); docs/MODEL.md section 9";
  j["query"] = terms_json(kQueryTermNames, t.coef.query, t.err.query);
  j["build"] = terms_json(kBuildTermNames, t.coef.build, t.err.build);
  j["fit_query"] = quality_json(t.query);
  j["fit_build"] = quality_json(t.build);
  j["fit_total"] = quality_json(t.total);
  j["holdout_query"] = quality_json(t.holdout_query);
  j["holdout_build"] = quality_json(t.holdout_build);
  j["holdout_total"] = quality_json(t.holdout_total);
  return j;
}

TimeModelFit time_from(const nlohmann::json& j) {
  TimeModelFit t;
  terms_from(j.at("query"), kQueryTermNames, t.coef.query, t.err.query);
  terms_from(j.at("build"), kBuildTermNames, t.coef.build, t.err.build);
  t.query = quality_from(j.at("fit_query"));
  t.build = quality_from(j.at("fit_build"));
  t.total = quality_from(j.at("fit_total"));
  t.holdout_query = quality_from(j.at("holdout_query"));
  t.holdout_build = quality_from(j.at("holdout_build"));
  t.holdout_total = quality_from(j.at("holdout_total"));
  return t;
}

}  // namespace

std::string calibration_path() {
  if (const char* p = env("HGRID_CALIBRATION")) return p;
  std::filesystem::path base;
  if (const char* x = env("XDG_CONFIG_HOME")) base = x;
  else if (const char* h = env("HOME")) base = std::filesystem::path(h) / ".config";
  else base = ".config";
  return (base / "hgridlab" / "calibration.json").string();
}

void save_calibration(const Calibration& c, const std::string& path) {
  // The file leads with where it was measured, then the time model (what
  // predicts seconds: count --repeat, recommend --cost time), then the
  // one-K fit that gives K for T = checks + K accesses (a coarser model of
  // the wall time: its r2 is not the time model's).
  nlohmann::ordered_json j;
  j["format"] = kFormat;
  j["machine"] = c.machine;
  j["date"] = c.date;
  j["git_hash"] = c.git_hash;
  j["compiler"] = c.compiler;
  j["preset"] = c.preset;
  for (int d = 2; d <= 3; ++d)
    if (const TimeModelFit* t = c.time_model(d)) j["time_model"][std::to_string(d) + "D"] = time_json(*t);
  j["model"] = "one-K fit, for K: query wall time W = c0 N + c_cell A + c_test C; K = c_cell / c_test";
  for (const auto& f : kNumbers) j[f.key] = c.*(f.member);
  j["points"] = c.points;
  j["units"] = "c0: seconds per particle, c_cell: seconds per cell access, c_test: seconds per narrow-phase check";
  j["r2_log"] = c.r2_log;
  const std::filesystem::path target(path);
  if (target.has_parent_path()) std::filesystem::create_directories(target.parent_path());
  write_text_atomically(path, j.dump(2) + "\n", "calibration");
}

Calibration load_calibration(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError("calibration", "no calibration file at '" + path + "'");
  std::stringstream buf;
  buf << in.rdbuf();
  const auto bad = [&](const std::string& why) {
    return InputError("calibration", "'" + path + "' is not a valid calibration file (" + why + ")");
  };
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(buf.str());
  } catch (const nlohmann::json::parse_error& e) {
    throw bad(std::string("invalid JSON: ") + e.what());
  }
  if (!j.is_object()) throw bad("not a JSON object");
  const std::string format = j.value("format", std::string());
  if (format != kFormat && format != kFormatV1)
    throw bad(std::string("'format' is not '") + kFormat + "' or '" + kFormatV1 + "'");
  Calibration c;
  for (const auto& f : kNumbers) {
    if (!j.contains(f.key) || !j[f.key].is_number()) throw bad(std::string("'") + f.key + "' missing or not a number");
    c.*(f.member) = j[f.key].get<double>();
  }
  if (!(std::isfinite(c.K) && c.K > 0)) throw bad("'K' must be finite and > 0");
  if (!(std::isfinite(c.K_err) && c.K_err >= 0)) throw bad("'K_err' must be finite and >= 0");
  const auto text = [&](const char* key) {
    return j.contains(key) && j[key].is_string() ? j[key].get<std::string>() : std::string();
  };
  c.points = j.contains("points") && j["points"].is_number_integer() ? j["points"].get<int>() : 0;
  c.machine = text("machine");
  c.date = text("date");
  c.git_hash = text("git_hash");
  c.compiler = text("compiler");
  c.preset = text("preset");
  if (j.contains("r2_log") && j["r2_log"].is_number()) c.r2_log = j["r2_log"].get<double>();
  if (format == kFormat && j.contains("time_model")) {
    for (int d = 2; d <= 3; ++d) {
      const std::string key = std::to_string(d) + "D";
      if (!j["time_model"].contains(key)) continue;
      try {
        c.time[d - 2] = time_from(j["time_model"][key]);
      } catch (const std::exception& e) {
        throw bad("'time_model." + key + "': " + e.what());
      }
    }
  }
  return c;
}

namespace {

/// The stored calibration, or InputError(field) saying what needed it
/// (`purpose`), why it cannot be read, and how to make one.
Calibration stored_or_explain(const std::string& field, const std::string& purpose) {
  const std::string path = calibration_path();
  try {
    return load_calibration(path);
  } catch (const InputError& e) {
    const std::string why = std::string(e.what()).substr(std::string("calibration: ").size());
    throw InputError(field, purpose + ", but " + why + "; run `hgrid calibrate` first (it writes " + path +
                                "; HGRID_CALIBRATION overrides the path)");
  }
}

}  // namespace

double calibrated_K(const std::string& field) {
  return stored_or_explain(field, "'auto' means the K measured on this machine").K;
}

TimeModelFit calibrated_time_model(int d, const std::string& field) {
  const Calibration c = stored_or_explain(field, "the time model is this machine's");
  if (!c.time_model(d))
    throw InputError(field, "the calibration at '" + calibration_path() + "' has no " + std::to_string(d) +
                                "D time model (written before it existed); run `hgrid calibrate` again");
  return *c.time_model(d);
}

CostKind parse_cost(const std::string& text, const std::string& field) {
  if (text == "count") return CostKind::count;
  if (text == "time") return CostKind::time;
  throw InputError(field, "must be 'count' (the paper's T = checks + K accesses) or 'time' (this machine's "
                          "predicted seconds; needs `hgrid calibrate`), got '" + text + "'");
}

std::optional<Calibration> stored_calibration() {
  try {
    return load_calibration(calibration_path());
  } catch (const InputError&) {
    return std::nullopt;
  }
}

double resolve_K(const std::string& text, const std::string& field) {
  if (text == "auto") return calibrated_K(field);
  std::size_t used = 0;
  double K = 0;
  try {
    K = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size())
    throw InputError(field, "must be a number >= 0 or 'auto' (got '" + text + "')");
  if (!(std::isfinite(K) && K >= 0)) throw InputError(field, "must be finite and >= 0 (got '" + text + "')");
  return K;
}

std::string machine_description() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("model name", 0) != 0) continue;
    const auto colon = line.find(':');
    if (colon == std::string::npos) break;
    const auto first = line.find_first_not_of(" \t", colon + 1);
    if (first != std::string::npos) return line.substr(first);
  }
  return "unknown";
}

}  // namespace hgrid
