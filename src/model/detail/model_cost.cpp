// Cost model T/N (docs/MODEL.md section 3): Eqs. (6), (9)-(16), (19)-(22), (27).
#include "hgridlab/model/detail/model_cost.hpp"

#include "hgridlab/grid/geometry.hpp"

#include <cmath>

namespace hgrid::detail {

namespace {
constexpr double kEdgeRelTol = 1e-12;

double ipow(double x, int n) {
  double r = 1.0;
  for (int i = 0; i < n; ++i) r *= x;
  return r;
}
}  // namespace

CostModel::CostModel(const Distribution& dist, const ModelParams& p) : dist_(dist), p_(p) {
  validate(p);
  nc_ = (p.d == 2) ? 4 : 13;
  const double vd = unit_ball_volume(p.d);
  vp_ = vd * dist.moment(p.d, 0.0, dist.r_max());  // mean particle volume
  c_ = p.nu / vp_;
  double binom = 1.0;
  for (int i = 0; i <= p.d; ++i) {
    coef_[i] = ipow(2.0, p.d) * binom;
    binom = binom * (p.d - i) / (i + 1);
  }
}

void CostModel::fill_levels(const std::vector<double>& s, std::vector<Level>& lv) const {
  const int L = static_cast<int>(s.size());
  lv.resize(L);
  double lo = 0.0;  // level 1 owns every radius <= s_1 / 2
  for (int h = 0; h < L; ++h) {
    const double hi = 0.5 * s[h];
    Level& v = lv[h];
    v.s = s[h];
    dist_.moments(p_.d, lo, hi, v.M.data());
    v.P = v.M[0];                              // P_h
    v.m = c_ * ipow(v.s, p_.d) * v.P;          // m_h = nu s_h^d P_h / V_p, Eq. (11)
    lo = hi;
  }
}

double CostModel::total(const std::vector<double>& s) const {
  thread_local std::vector<Level> lv;
  fill_levels(s, lv);
  const int L = static_cast<int>(s.size()), d = p_.d;
  const double K = p_.K;
  std::array<double, kMaxD + 1> S{};  // sum over searched levels j of (m_j + K) s_j^-i
  double T = 0.0;
  for (int step = 0; step < L; ++step) {
    const int h = p_.search == Search::top_down ? step : L - 1 - step;
    const Level& v = lv[h];
    // Own level, Eqs. (12)-(15): N_h [(1/2 + n_c) m_h + K (1 + n_c)].
    T += v.P * ((0.5 + nc_) * v.m + K * (1.0 + nc_));
    // Cross levels, Eqs. (16), (19)-(22): sum_j (m_j + K) P_h b(j,h).
    for (int i = 0; i <= d; ++i) T += coef_[i] * v.M[i] * S[i];
    double inv = 1.0;
    for (int i = 0; i <= d; ++i, inv /= v.s) S[i] += (v.m + K) * inv;
  }
  return T;
}

double CostModel::total_and_gradient(const std::vector<double>& s, std::vector<double>& grad) const {
  thread_local std::vector<Level> lv;
  thread_local std::vector<std::array<double, kMaxD + 1>> S, R;
  fill_levels(s, lv);
  const int L = static_cast<int>(s.size()), d = p_.d;
  const double K = p_.K;
  const bool td = p_.search == Search::top_down;
  S.assign(L, {});
  R.assign(L, {});
  // S_i(h) = sum_{j in J(h)} (m_j + K) s_j^-i ; R_i(j) = sum_{h : j in J(h)} M_i^h.
  std::array<double, kMaxD + 1> acc{}, accR{};
  double T = 0.0;
  for (int step = 0; step < L; ++step) {
    const int h = td ? step : L - 1 - step;
    const Level& v = lv[h];
    S[h] = acc;
    T += v.P * ((0.5 + nc_) * v.m + K * (1.0 + nc_));
    for (int i = 0; i <= d; ++i) T += coef_[i] * v.M[i] * acc[i];
    double inv = 1.0;
    for (int i = 0; i <= d; ++i, inv /= v.s) acc[i] += (v.m + K) * inv;
  }
  for (int step = 0; step < L; ++step) {
    const int j = td ? L - 1 - step : step;
    R[j] = accR;
    for (int i = 0; i <= d; ++i) accR[i] += lv[j].M[i];
  }
  // Adjoints: dT/dP_h, dT/dM_i^h (i >= 1) and the explicit dT/ds_h.
  thread_local std::vector<double> DP, Ds;
  DP.assign(L, 0.0);
  Ds.assign(L, 0.0);
  for (int h = 0; h < L; ++h) {
    const Level& v = lv[h];
    double G = v.P * (0.5 + nc_), Dexp = 0.0, inv = 1.0;  // G = dT/dm_h
    for (int i = 0; i <= d; ++i, inv /= v.s) {
      G += coef_[i] * inv * R[h][i];
      Dexp -= coef_[i] * i * inv / v.s * R[h][i];
    }
    Dexp *= (v.m + K);
    DP[h] = (0.5 + nc_) * v.m + K * (1.0 + nc_) + coef_[0] * S[h][0] + G * c_ * ipow(v.s, d);
    Ds[h] = Dexp + G * c_ * d * ipow(v.s, d - 1) * v.P;
  }
  grad.assign(L, 0.0);
  for (int k = 0; k < L; ++k) {
    // s_k is the upper end of level k and the lower end of level k+1.
    // One-sided at the ends: a size that rounds to just below 2 r_min (e.g.
    // exp(log(s_0))) still gains particles when it grows.
    double rho = 0.5 * s[k];
    if (rho < dist_.r_min() && rho >= dist_.r_min() * (1.0 - kEdgeRelTol)) rho = dist_.r_min();
    const double f = 0.5 * dist_.pdf(rho);
    double up = DP[k], dn = (k + 1 < L) ? DP[k + 1] : 0.0, rp = 1.0;
    for (int i = 1; i <= d; ++i) {
      rp *= rho;
      up += coef_[i] * S[k][i] * rp;
      if (k + 1 < L) dn += coef_[i] * S[k + 1][i] * rp;
    }
    grad[k] = Ds[k] + f * (up - dn);
  }
  return T;
}

ModelResult CostModel::detailed(const std::vector<double>& s) const {
  std::vector<Level> lv;
  fill_levels(s, lv);
  const int L = static_cast<int>(s.size()), d = p_.d;
  ModelResult r;
  r.sizes = s;
  r.P.resize(L);
  r.m.resize(L);
  r.T_cd.assign(L, 0.0);
  r.T_ca.assign(L, 0.0);
  r.T_cd_pair.assign(static_cast<std::size_t>(L) * L, 0.0);
  std::array<double, kMaxD + 1> Sm{}, S1{};  // sums of m_j s_j^-i and of s_j^-i
  for (int step = 0; step < L; ++step) {
    const int h = p_.search == Search::top_down ? step : L - 1 - step;
    const Level& v = lv[h];
    r.P[h] = v.P;
    r.m[h] = v.m;
    double cd = v.P * (0.5 + nc_) * v.m, ca = v.P * (1.0 + nc_);
    r.T_cd_pair[h * L + h] = cd;
    for (int prev = 0; prev < step; ++prev) {  // the levels searched before: b(j,h) m_j P_h
      const int j = p_.search == Search::top_down ? prev : L - 1 - prev;
      double pair = 0.0, inv = 1.0;
      for (int i = 0; i <= d; ++i, inv /= lv[j].s) pair += coef_[i] * v.M[i] * inv;
      r.T_cd_pair[h * L + j] = pair * lv[j].m;
    }
    for (int i = 0; i <= d; ++i) {
      cd += coef_[i] * v.M[i] * Sm[i];
      ca += coef_[i] * v.M[i] * S1[i];
    }
    r.T_cd[h] = cd;
    r.T_ca[h] = ca;
    r.T_cd_over_N += cd;
    r.T_ca_over_N += ca;
    double inv = 1.0;
    for (int i = 0; i <= d; ++i, inv /= v.s) {
      Sm[i] += v.m * inv;
      S1[i] += inv;
    }
  }
  r.T_over_N = r.T_cd_over_N + p_.K * r.T_ca_over_N;
  return r;
}

}  // namespace hgrid::detail
