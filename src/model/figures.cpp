// Data of Figs. 2-10 (docs/MODEL.md section 6) and Fig. 13 (accuracy vs time).
#include "hgridlab/model/figures.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>
#include <vector>

#include "hgridlab/model/cell_sizes.hpp"
#include "hgridlab/base/clock.hpp"
#include "hgridlab/base/error.hpp"

namespace hgrid {

namespace {
constexpr int kOmegaPerDecade = 10;   // Figs. 3-8: omega = 10^(k/10), 1 .. 1000
constexpr int kOmegaDecades = 3;
constexpr int kMaxLevelsPlotted = 30;  // Figs. 6 and 9
constexpr int kInsetMaxLevels = 40;    // Fig. 6 inset: min over L = 1..40
constexpr double kTimingMinSeconds = 0.05;  // Fig. 13: repeat each timing this long

const CellMethod kMethods[] = {CellMethod::linear, CellMethod::exponential, CellMethod::constant,
                               CellMethod::optimal};

struct Csv {
  std::ostringstream body;
  const FigureSink& out;
  std::string name;
  Csv(const FigureSink& o, const std::string& n, const std::string& header) : out(o), name(n) {
    body.precision(10);
    body << "# hgridlab model data for " << name << "\n" << header << "\n";
  }
  void commit() const { out(name, body.str()); }
};

std::vector<double> omegas() {
  std::vector<double> w;
  for (int k = 0; k <= kOmegaPerDecade * kOmegaDecades; ++k) w.push_back(std::pow(10.0, double(k) / kOmegaPerDecade));
  return w;
}

ModelParams params(Search s = Search::top_down) {
  ModelParams p;  // d = 3, nu = 0.7, K = 0.2 (docs/MODEL.md section 3)
  p.search = s;
  return p;
}
const char* kParamHeader = "# d=3\n# nu=0.7\n# K=0.2";

void fig02(const FigureSink& dir) {
  Csv c(dir, "fig02-pdf.csv", "# omega=3\n# columns=r/r_min,f(alpha=0),f(-1),f(-2),f(-3)");
  const double a[] = {0.0, -1.0, -2.0, -3.0};
  for (int i = 0; i <= 400; ++i) {
    const double r = 1.0 + 2.0 * i / 400.0;
    c.body << r;
    for (double al : a) c.body << "," << PowerLaw(al, 3.0).pdf(r);
    c.body << "\n";
  }
  c.commit();
}

void fig03(const FigureSink& dir) {
  Csv c(dir, "fig03-single-level.csv",
        std::string(kParamHeader) + "\n# L=1 (linked cell), s_1=2 r_max\n# columns=omega,T/N(alpha=0),T/N(-1),T/N(-2),T/N(-3)");
  for (double w : omegas()) {
    c.body << w;
    for (double al : {0.0, -1.0, -2.0, -3.0})
      c.body << "," << evaluate_model(PowerLaw(al, w), params(), {2.0 * w}).T_over_N;
    c.body << "\n";
  }
  c.commit();
}

/// Figs. 4, 5, 7, 8: T*/N and L* against omega, alpha = 0, -3, TD and BU.
void fig_best_vs_omega(const FigureSink& dir, const std::string& name, CellMethod m) {
  Csv c(dir, name,
        std::string(kParamHeader) + "\n# cells=" + to_string(m) +
            (m == CellMethod::constant ? "\n# q=1" : "") +
            "\n# columns=omega,T_td_a0,L_td_a0,T_td_a-3,L_td_a-3,T_bu_a0,L_bu_a0,T_bu_a-3,L_bu_a-3");
  for (double w : omegas()) {
    c.body << w;
    for (Search s : {Search::top_down, Search::bottom_up})
      for (double al : {0.0, -3.0}) {
        const auto ch = choose_cell_sizes(PowerLaw(al, w), params(s), m);
        c.body << "," << ch.model.T_over_N << "," << ch.levels;
      }
    c.body << "\n";
  }
  c.commit();
}

void fig06(const FigureSink& dir) {
  const PowerLaw f(-3.0, 100.0);
  Csv c(dir, "fig06-constant-q.csv",
        std::string(kParamHeader) + "\n# omega=100\n# alpha=-3\n# search=topdown\n# columns=L,T(q=0.5),T(q=1),T(q=2),T(q=5)");
  std::vector<std::vector<double>> T;
  for (double q : {0.5, 1.0, 2.0, 5.0}) T.push_back(cost_versus_levels(f, params(), CellMethod::constant, kMaxLevelsPlotted, q));
  for (int L = 1; L <= kMaxLevelsPlotted; ++L) {
    c.body << L;
    for (const auto& v : T) c.body << "," << v[L - 1];
    c.body << "\n";
  }
  c.commit();
  Csv in(dir, "fig06-inset-min-vs-q.csv",
         std::string(kParamHeader) + "\n# omega=100\n# alpha=-3\n# search=topdown\n# min over L = 1..40\n# columns=q,min_L T/N,L*");
  for (int k = -8; k <= 12; ++k) {  // q = 0.25 .. 8
    const double q = std::pow(2.0, k / 4.0);
    const auto v = cost_versus_levels(f, params(), CellMethod::constant, kInsetMaxLevels, q);
    const auto best = std::min_element(v.begin(), v.end());
    in.body << q << "," << *best << "," << (best - v.begin()) + 1 << "\n";
  }
  in.commit();
}

void fig09(const FigureSink& dir) {
  const PowerLaw f(-3.0, 100.0);
  Csv c(dir, "fig09-methods-vs-L.csv",
        std::string(kParamHeader) + "\n# omega=100\n# alpha=-3\n# search=topdown\n# q=1\n# columns=L,linear,exponential,constant,optimal");
  std::vector<std::vector<double>> T;
  for (CellMethod m : kMethods) T.push_back(cost_versus_levels(f, params(), m, kMaxLevelsPlotted));
  for (int L = 1; L <= kMaxLevelsPlotted; ++L) {
    c.body << L;
    for (const auto& v : T) c.body << "," << v[L - 1];
    c.body << "\n";
  }
  c.commit();
}

void fig10(const FigureSink& dir) {
  const PowerLaw f(-3.0, 100.0);
  for (CellMethod m : kMethods) {
    const auto ch = choose_cell_sizes(f, params(), m);
    Csv c(dir, std::string("fig10-profile-") + to_string(m) + ".csv",
          std::string(kParamHeader) + "\n# omega=100\n# alpha=-3\n# search=topdown\n# L*=" +
              std::to_string(ch.levels) + "\n# T/N=" + std::to_string(ch.model.T_over_N) +
              "\n# columns=h,h/L*,s_h/r_min,m_h");
    for (int h = 0; h < ch.levels; ++h)
      c.body << h + 1 << "," << double(h + 1) / ch.levels << "," << ch.sizes[h] / f.r_min() << ","
             << ch.model.m[h] << "\n";
    c.commit();
  }
}

/// Fig. 13: time to choose the sizes (with L*) against the excess of T over
/// the optimum, every method, a few distributions.
void fig13(const FigureSink& dir, const std::optional<TimeCoefficients>& time) {
  Csv c(dir, "fig13-accuracy-time.csv",
        std::string(kParamHeader) + "\n# search=topdown\n# q=1\n# time: wall clock of choose_cell_sizes() with the L* search, one thread"
                                    "\n# method_index 4: time_optimal_sizes() for N = 1e6 with the given time model" +
            (time ? "" : " (none given: no rows)") +
            "\n# columns=method_index,alpha,omega,seconds,T/N,excess_over_optimal,L*");
  int mi = 0;
  for (CellMethod m : kMethods) {
    for (double al : {0.0, -3.0})
      for (double w : {10.0, 100.0, 1000.0}) {
        const PowerLaw f(al, w);
        const double T_opt = choose_cell_sizes(f, params(), CellMethod::optimal).model.T_over_N;
        SizeChoice ch;
        int reps = 0;
        const auto t0 = Clock::now();
        double secs = 0.0;
        do {
          ch = choose_cell_sizes(f, params(), m);
          ++reps;
          secs = seconds_since(t0);
        } while (secs < kTimingMinSeconds);
        c.body << mi << "," << al << "," << w << "," << secs / reps << "," << ch.model.T_over_N << ","
               << ch.model.T_over_N / T_opt - 1.0 << "," << ch.levels << "\n";
      }
    ++mi;
  }
  if (time)  // the sizes that minimise predicted seconds, costed in the paper's T
    for (double al : {0.0, -3.0})
      for (double w : {10.0, 100.0, 1000.0}) {
        const PowerLaw f(al, w);
        const double T_opt = choose_cell_sizes(f, params(), CellMethod::optimal).model.T_over_N;
        const auto t0 = Clock::now();
        const TimeOptimalSizes t = time_optimal_sizes(f, params(), *time, kFig13Particles);
        const double secs = seconds_since(t0);
        const double T = evaluate_model(f, params(), t.sizes).T_over_N;
        c.body << mi << "," << al << "," << w << "," << secs << "," << T << "," << T / T_opt - 1.0 << ","
               << t.sizes.size() << "\n";
      }
  c.commit();
}
}  // namespace

void write_model_figures(const FigureSink& dir, const std::string& only, std::ostream& log,
                         const std::optional<TimeCoefficients>& time) {
  std::set<int> want;
  if (!only.empty()) {
    std::stringstream ss(only);
    std::string item;
    while (std::getline(ss, item, ',')) {
      int n = 0;
      try {
        n = std::stoi(item);
      } catch (const std::exception&) {
        n = -1;
      }
      if (n < 2 || (n > 10 && n != 13)) throw InputError("only", "figure numbers are 2..10 and 13 (got '" + item + "')");
      want.insert(n);
    }
  }
  std::vector<std::pair<int, std::function<void()>>> jobs = {
      {8, [&] { fig_best_vs_omega(dir, "fig08-optimal.csv", CellMethod::optimal); }},
      {7, [&] { fig_best_vs_omega(dir, "fig07-constant.csv", CellMethod::constant); }},
      {4, [&] { fig_best_vs_omega(dir, "fig04-linear.csv", CellMethod::linear); }},
      {5, [&] { fig_best_vs_omega(dir, "fig05-exponential.csv", CellMethod::exponential); }},
      {6, [&] { fig06(dir); }},
      {9, [&] { fig09(dir); }},
      {10, [&] { fig10(dir); }},
      {2, [&] { fig02(dir); }},
      {3, [&] { fig03(dir); }},
  };
  std::mutex mu;
  std::atomic<std::size_t> next{0};
  std::exception_ptr err;
  auto worker = [&] {
    for (std::size_t i; (i = next++) < jobs.size();) {
      if (!want.empty() && !want.count(jobs[i].first)) continue;
      const auto t0 = Clock::now();
      try {
        jobs[i].second();
      } catch (...) {
        std::lock_guard<std::mutex> lk(mu);
        if (!err) err = std::current_exception();
        return;
      }
      std::lock_guard<std::mutex> lk(mu);
      log << "modelfigs: fig " << jobs[i].first << " data in "
          << seconds_since(t0) << " s\n";
    }
  };
  std::thread other(worker);
  worker();
  other.join();
  if (err) std::rethrow_exception(err);
  if (want.empty() || want.count(13)) {  // timings alone, after the rest
    const auto t0 = Clock::now();
    fig13(dir, time);
    log << "modelfigs: fig 13 data in "
        << seconds_since(t0) << " s\n";
  }
}

}  // namespace hgrid
