// The time loop of one composition of effects: velocity Verlet (half kick,
// drift, forces, half kick), contacts from a contact list
// (contacts/contact_list.hpp) over the HGrid.
//
// The list keeps the candidate pairs within r_i + r_j + skin and hands over,
// at every step, exactly the pairs that touch, tested with the grid's own
// expression: the same set, bit for bit, as a grid rebuilt every step. It is
// rebuilt (the grid rebuilt in place) only when a particle may have moved
// through its skin; with skin 0 (the default) it is rebuilt every step.
// The list, the grid and the force buffers are kept between steps, so that
// a step allocates nothing: with fresh arrays every step, glibc's malloc
// handed memory back to the kernel and took it again, and the page faults
// cost more than the step's work on some machines.
//
// Velocity-dependent forces (dashpot, friction) use the predicted velocity
// v_n + dt a_n (second order), so the restitution of a resolved contact
// converges as dt^2.
//
// Contacts are handled in canonical order, (i, j) ascending, not in the
// order the grid finds them: a particle's forces are summed in an order that
// does not depend on the cell sizes, the number of levels, the search
// direction, the skin or the grid's internals, so the trajectory is a
// property of the scene alone (the optimal grid and the linked cell, with
// any skin, run the same simulation, bit for bit). The list's contacts come
// in that order. On several threads the forces and the sums run on all of
// them and still add every particle's contributions in canonical order
// (contacts/pair_sum.hpp), so the trajectory is also the same for any
// number of threads.
#pragma once
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "hgridlab/base/clock.hpp"
#include "hgridlab/dpm/contact_law.hpp"
#include "hgridlab/dpm/simulation.hpp"
#include "hgridlab/grid/hgrid.hpp"
#include "hgridlab/contacts/contact_history.hpp"
#include "hgridlab/contacts/contact_list.hpp"
#include "hgridlab/contacts/pair_sum.hpp"

namespace hgrid::dpm {

template <int D>
using Vec = std::array<double, D>;

/// Angular velocity: a scalar (z) in 2D, a vector in 3D.
template <int D>
using Spin = std::array<double, D == 2 ? 1 : 3>;

template <int D>
inline Spin<D> cross_rn(const Vec<D>& n, const Vec<D>& f) {  // n x f
  if constexpr (D == 2) return {n[0] * f[1] - n[1] * f[0]};
  else return {n[1] * f[2] - n[2] * f[1], n[2] * f[0] - n[0] * f[2], n[0] * f[1] - n[1] * f[0]};
}
template <int D>
inline Vec<D> cross_wn(const Spin<D>& w, const Vec<D>& n) {  // w x n
  if constexpr (D == 2) return {-w[0] * n[1], w[0] * n[0]};
  else return {w[1] * n[2] - w[2] * n[1], w[2] * n[0] - w[0] * n[2], w[0] * n[1] - w[1] * n[0]};
}

template <int D, Boundary B, bool Friction, bool Gravity>
class Engine final : public Simulation {

 public:
  Engine(const DpmConfig& c, const Packing& p, const std::vector<double>& vel)
      : c_(c), law_(SpringDashpot::from(c.contact_time, c.restitution)), s_(p.spheres<D>()), sum_(s_.size()) {
    for (int k = 0; k < D; ++k) box_[k] = c.box[k];
    const std::size_t n = s_.size();
    v_.assign(n, Vec<D>{});
    f_.assign(n, Vec<D>{});
    m_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      for (int k = 0; k < D; ++k) v_[i][k] = vel.empty() ? 0.0 : vel[i * D + k];
      const double r = s_[i].r;
      m_[i] = c.density * (D == 2 ? M_PI * r * r : 4.0 / 3.0 * M_PI * r * r * r);
    }
    if constexpr (Friction) {
      w_.assign(n, Spin<D>{});
      tq_.assign(n, Spin<D>{});
      tqnew_.assign(n, Spin<D>{});
      inv_I_.resize(n);
      for (std::size_t i = 0; i < n; ++i)
        inv_I_[i] = 1.0 / ((D == 2 ? 0.5 : 0.4) * m_[i] * s_[i].r * s_[i].r);
    }
    threads_ = resolve_threads(c.threads);
    ListBox<D> lb;
    lb.side = box_;
    lb.periodic.fill(B == Boundary::periodic);
    list_.emplace(lb, ContactListParams{c.sizes, c.search, c.threads, c.skin, 0.0});
    compute_forces();  // the initial forces: no spring grows (spring_dt_ = 0)
    spring_dt_ = c.dt;
  }

  void run(std::uint64_t steps) override {
    const double dt = c_.dt, h = 0.5 * dt;
    for (std::uint64_t n = 0; n < steps; ++n) {
      auto t0 = Clock::now();
      const std::ptrdiff_t n_particles = static_cast<std::ptrdiff_t>(s_.size());
#if defined(_OPENMP)
#pragma omp parallel for schedule(static) num_threads(threads_) if (threads_ > 1)
#endif
      for (std::ptrdiff_t ii = 0; ii < n_particles; ++ii) {
        const auto i = static_cast<std::size_t>(ii);
        const double im = 1.0 / m_[i];
        for (int k = 0; k < D; ++k) {
          v_[i][k] += h * f_[i][k] * im;
          double x = s_[i].x[k] + dt * v_[i][k];
          if constexpr (B == Boundary::periodic) x = detail::wrap(x, box_[k]);
          s_[i].x[k] = x;
        }
        if constexpr (Friction)
          for (std::size_t k = 0; k < w_[i].size(); ++k) w_[i][k] += h * tq_[i][k] * inv_I_[i];
      }
      stats_.seconds_integration += seconds_since(t0);
      time_ += dt;
      compute_forces();
      t0 = Clock::now();
#if defined(_OPENMP)
#pragma omp parallel for schedule(static) num_threads(threads_) if (threads_ > 1)
#endif
      for (std::ptrdiff_t ii = 0; ii < n_particles; ++ii) {
        const auto i = static_cast<std::size_t>(ii);
        const double im = 1.0 / m_[i];
        for (int k = 0; k < D; ++k) v_[i][k] += h * f_[i][k] * im;
        if constexpr (Friction)
          for (std::size_t k = 0; k < w_[i].size(); ++k) w_[i][k] += h * tq_[i][k] * inv_I_[i];
      }
      stats_.seconds_integration += seconds_since(t0);
      ++stats_.steps;
    }
  }

  double time() const override { return time_; }

  double kinetic_energy() const override {
    double e = 0;
    for (std::size_t i = 0; i < s_.size(); ++i) {
      double v2 = 0;
      for (int k = 0; k < D; ++k) v2 += v_[i][k] * v_[i][k];
      e += 0.5 * m_[i] * v2;
      if constexpr (Friction) {
        double w2 = 0;
        for (double w : w_[i]) w2 += w * w;
        e += 0.5 * w2 / inv_I_[i];
      }
    }
    return e;
  }

  double elastic_energy() const override {
    double e = 0;
    list_->for_each_contact([&](std::uint32_t i, std::uint32_t j) {  // the contacts of the current positions
      const double dist = std::sqrt(detail::dist2<D, B>(s_[i].x, s_[j].x, box_));
      e += law_.energy(m_[i] * m_[j] / (m_[i] + m_[j]), s_[i].r + s_[j].r - dist);
    });
    if constexpr (B == Boundary::walls)
      for (std::size_t i = 0; i < s_.size(); ++i)
        for (int k = 0; k < D; ++k) {
          const double lo = s_[i].r - s_[i].x[k], hi = s_[i].x[k] + s_[i].r - box_[k];
          if (lo > 0) e += law_.energy(m_[i], lo);
          if (hi > 0) e += law_.energy(m_[i], hi);
        }
    return e;
  }

  std::array<double, 3> momentum() const override {
    std::array<double, 3> p{};
    for (std::size_t i = 0; i < s_.size(); ++i)
      for (int k = 0; k < D; ++k) p[k] += m_[i] * v_[i][k];
    return p;
  }
  std::vector<double> positions() const override {
    std::vector<double> out(s_.size() * D);
    for (std::size_t i = 0; i < s_.size(); ++i)
      for (int k = 0; k < D; ++k) out[i * D + k] = s_[i].x[k];
    return out;
  }
  std::vector<double> velocities() const override {
    std::vector<double> out(s_.size() * D);
    for (std::size_t i = 0; i < s_.size(); ++i)
      for (int k = 0; k < D; ++k) out[i * D + k] = v_[i][k];
    return out;
  }
  const StepStats& stats() const override { return stats_; }

 private:

  /// Predicted end-of-step velocity v_n + dt a_n (v_ holds v_{n+1/2} here).
  Vec<D> vpred(std::size_t i) const {
    Vec<D> v;
    const double h = 0.5 * c_.dt / m_[i];
    for (int k = 0; k < D; ++k) v[k] = v_[i][k] + h * f_[i][k];
    return v;
  }
  Spin<D> wpred(std::size_t i) const {
    Spin<D> w = w_[i];
    for (std::size_t k = 0; k < w.size(); ++k) w[k] += 0.5 * c_.dt * tq_[i][k] * inv_I_[i];
    return w;
  }

  /// Tangential force on the particle whose contact point sees the partner
  /// move with relative velocity vrel, normal n, normal force fn >= 0:
  /// viscous, capped by Coulomb's mu * fn.
  Vec<D> tangential(const Vec<D>& vrel, const Vec<D>& n, double m, double fn) const {
    double vn = 0;
    for (int k = 0; k < D; ++k) vn += vrel[k] * n[k];
    Vec<D> vt;
    double vt2 = 0;
    for (int k = 0; k < D; ++k) {
      vt[k] = vrel[k] - vn * n[k];
      vt2 += vt[k] * vt[k];
    }
    const double visc = c_.friction_damping * m / c_.contact_time;
    const double vtn = std::sqrt(vt2), cap = c_.mu * fn;
    const double scale = visc * vtn > cap && vtn > 0 ? cap / vtn : visc;
    for (int k = 0; k < D; ++k) vt[k] *= scale;
    return vt;
  }

  /// What pair (i, j) contributes: normal force fn n on j (-fn n on i); with
  /// friction, tangential force ft on i (-ft on j) and the arm n x ft, whose
  /// torque is r times it on each.
  struct NormalForce {
    Vec<D> fn;
  };
  struct FullForce {
    Vec<D> fn, ft;
    Spin<D> arm;
  };
  using PairForce = std::conditional_t<Friction, FullForce, NormalForce>;

  /// Tangential spring force on i (the law of TangentialLaw::spring): xi,
  /// the contact's displacement, is rotated into the tangent plane, grown by
  /// vt dt and, if the force passes Coulomb's cap, set back to the cap.
  Vec<D> tangential_spring(const Vec<D>& vrel, const Vec<D>& n, double m, double fn, Vec<D>& xi) const {
    double vn = 0, xn = 0;
    for (int k = 0; k < D; ++k) {
      vn += vrel[k] * n[k];
      xn += xi[k] * n[k];
    }
    const double kt = c_.tangential_stiffness * law_.k_per_mass * m;
    const double gt = c_.friction_damping * m / c_.contact_time;
    Vec<D> vt, ft;
    double f2 = 0;
    for (int k = 0; k < D; ++k) {
      vt[k] = vrel[k] - vn * n[k];
      xi[k] = xi[k] - xn * n[k] + spring_dt_ * vt[k];
      ft[k] = kt * xi[k] + gt * vt[k];
      f2 += ft[k] * ft[k];
    }
    const double cap = c_.mu * fn, f = std::sqrt(f2);
    if (f > cap) {  // sliding: the force at the cap, the spring as long as that force allows
      const double scale = f > 0 ? cap / f : 0.0;
      for (int k = 0; k < D; ++k) {
        ft[k] *= scale;
        xi[k] = (ft[k] - gt * vt[k]) / kt;
      }
    }
    return ft;
  }

  PairForce pair_force(std::uint32_t i, std::uint32_t j, std::size_t k_pair) const {
    (void)k_pair;  // the contact's spring, with TangentialLaw::spring
    PairForce out;
    Vec<D> d;
    double d2 = 0;
    for (int k = 0; k < D; ++k) {
      d[k] = s_[j].x[k] - s_[i].x[k];
      if constexpr (B == Boundary::periodic) d[k] = detail::min_image(d[k], box_[k]);
      d2 += d[k] * d[k];
    }
    const double dist = std::sqrt(d2);
    Vec<D> nrm;
    for (int k = 0; k < D; ++k) nrm[k] = d[k] / dist;
    const Vec<D> vi = vpred(i), vj = vpred(j);
    Vec<D> vrel;
    double rate = 0;  // d(overlap)/dt = -(vj - vi).n
    for (int k = 0; k < D; ++k) {
      vrel[k] = vj[k] - vi[k];
      rate -= vrel[k] * nrm[k];
    }
    const double m = m_[i] * m_[j] / (m_[i] + m_[j]);
    const double fn = law_.force(m, s_[i].r + s_[j].r - dist, rate);
    for (int k = 0; k < D; ++k) out.fn[k] = fn * nrm[k];
    if constexpr (Friction) {
      const Spin<D> wi = wpred(i), wj = wpred(j);
      Spin<D> ws;
      for (std::size_t k = 0; k < ws.size(); ++k) ws[k] = s_[i].r * wi[k] + s_[j].r * wj[k];
      const Vec<D> rot = cross_wn<D>(ws, nrm);
      for (int k = 0; k < D; ++k) vrel[k] -= rot[k];
      out.ft = spring_ ? tangential_spring(vrel, nrm, m, std::max(fn, 0.0), spring_[k_pair])
                       : tangential(vrel, nrm, m, std::max(fn, 0.0));  // on i
      out.arm = cross_rn<D>(nrm, out.ft);
    }
    return out;
  }

  void compute_forces() {
    try {
      list_->update(s_);
    } catch (const InputError& e) {  // a particle left the walled box
      throw std::runtime_error("dpm: " + e.problem() + " at t = " + std::to_string(time_) +
                               " (time step too large for the velocities?)");
    }
    if constexpr (Friction)
      if (c_.tangential == TangentialLaw::spring) {  // the springs of the contacts that persist, carried
        history_.update(*list_);
        spring_ = history_.values().data();
      }
    const ContactListStats& ls = list_->stats();
    stats_.list_builds = ls.builds;
    stats_.list = ls;
    stats_.seconds_grid_build = ls.seconds_grid;
    stats_.seconds_query = ls.seconds() - ls.seconds_grid;  // the search, the skin check, the test
    stats_.seconds_contact_detection = ls.seconds();

    // Canonical order, then every particle's forces: gravity, its pairs in
    // canonical order, the walls (the same additions in the same order on
    // any number of threads).
    const auto t0 = Clock::now();
    sum_.assign_rows(list_->start(), list_->partners(), threads_);
    const std::size_t n = s_.size();
    std::vector<Vec<D>>& fnew = fnew_;
    fnew.resize(n);  // keeps its capacity: f_ and fnew_ swap every step (as tq_ and tqnew_)
    if constexpr (Friction) tqnew_.resize(n);
    std::atomic<std::uint64_t> wall_contacts{0};
    sum_.sum(
        pair_forces_, [&](std::uint32_t i, std::uint32_t j, std::size_t k) { return pair_force(i, j, k); },
        [&](std::size_t p) {
          if constexpr (Gravity)
            for (int k = 0; k < D; ++k) fnew[p][k] = m_[p] * c_.g[k];
          else fnew[p] = Vec<D>{};
          if constexpr (Friction) tqnew_[p] = Spin<D>{};
        },
        [&](const PairForce& r, std::size_t i) {  // i is the pair's first particle
          for (int k = 0; k < D; ++k) fnew[i][k] -= r.fn[k];
          if constexpr (Friction) {
            for (int k = 0; k < D; ++k) fnew[i][k] += r.ft[k];
            for (std::size_t k = 0; k < r.arm.size(); ++k) tqnew_[i][k] += s_[i].r * r.arm[k];
          }
        },
        [&](const PairForce& r, std::size_t j) {  // j is the pair's second particle
          for (int k = 0; k < D; ++k) fnew[j][k] += r.fn[k];
          if constexpr (Friction) {
            for (int k = 0; k < D; ++k) fnew[j][k] -= r.ft[k];
            for (std::size_t k = 0; k < r.arm.size(); ++k) tqnew_[j][k] += s_[j].r * r.arm[k];
          }
        },
        [&](std::size_t p) {
          if constexpr (B == Boundary::walls) {
            const std::uint64_t w = wall_force(p, fnew[p]);
            if (w > 0) wall_contacts.fetch_add(w, std::memory_order_relaxed);
          }
        });
    const std::uint64_t pairs = sum_.keys().size();
    stats_.pair_contacts += pairs;
    stats_.wall_contacts += wall_contacts.load();
    if constexpr (Gravity) stats_.gravity_evaluations += n;
    if constexpr (Friction) stats_.friction_evaluations += pairs + wall_contacts.load();
    f_.swap(fnew);
    if constexpr (Friction) tq_.swap(tqnew_);
    stats_.seconds_forces += seconds_since(t0);
  }

  /// Adds the walls' forces (and torques) on particle i to f; returns its
  /// number of wall contacts. Throws if it left the box.
  std::uint64_t wall_force(std::size_t i, Vec<D>& f) {
    std::uint64_t contacts = 0;
    for (int k = 0; k < D; ++k) {
      const double x = s_[i].x[k], r = s_[i].r;
      if (x < 0.0 || x > box_[k])
        throw std::runtime_error("dpm: particle " + std::to_string(i) + " left the walled box at t = " +
                                 std::to_string(time_) + " (time step too large for the velocities?)");
      for (int side = 0; side < 2; ++side) {
        const double overlap = side == 0 ? r - x : x + r - box_[k];
        if (overlap <= 0) continue;
        ++contacts;
        Vec<D> nrm{};  // from the particle towards the wall
        nrm[k] = side == 0 ? -1.0 : 1.0;
        const Vec<D> v = vpred(i);
        const double fn = law_.force(m_[i], overlap, v[k] * nrm[k]);
        f[k] -= fn * nrm[k];
        if constexpr (Friction) {
          // The wall is at rest; its contact point sees the particle's contact point move.
          Vec<D> vrel;
          const Vec<D> rot = cross_wn<D>(wpred(i), nrm);
          for (int a = 0; a < D; ++a) vrel[a] = -(v[a] + r * rot[a]);
          const Vec<D> ft = tangential(vrel, nrm, m_[i], std::max(fn, 0.0));
          const Spin<D> arm = cross_rn<D>(nrm, ft);
          for (int a = 0; a < D; ++a) f[a] += ft[a];
          for (std::size_t a = 0; a < arm.size(); ++a) tqnew_[i][a] += r * arm[a];
        }
      }
    }
    return contacts;
  }

  DpmConfig c_;
  SpringDashpot law_;
  Extent<D> box_{};
  std::vector<Sphere<D>> s_;
  std::vector<Vec<D>> v_, f_;
  std::vector<double> m_;
  std::vector<Spin<D>> w_, tq_, tqnew_;  // only with friction (tqnew_: the torques being computed)
  std::vector<double> inv_I_;
  PairSum sum_;                          // this step's contact pairs in canonical order
  std::vector<PairForce> pair_forces_;   // scratch of the threaded force pass
  int threads_ = 1;
  std::optional<ContactList<D>> list_;   // kept between steps
  ContactHistory<Vec<D>> history_;       // the tangential springs (TangentialLaw::spring)
  Vec<D>* spring_ = nullptr;             // history_'s values, one per contact of this step
  double spring_dt_ = 0;                 // how long a spring grows per step (0 for the initial forces)
  std::vector<Vec<D>> fnew_;         // the forces being computed (swapped with f_)
  StepStats stats_;
  double time_ = 0;
};

}  // namespace hgrid::dpm
