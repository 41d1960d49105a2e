// STEP and ICE identification of the modal cubic stiffness (see cubic_fit.h
// for the model, units and references).
#include "reduced/cubic_fit.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace beamslider
{
  namespace
  {
    // Dense storage of the sorted coefficients while they are being computed:
    // N ≤ 10 modes in practice, so N⁴ doubles are nothing.
    class CubicTable
    {
    public:
      explicit CubicTable(const unsigned int N)
        : N_(N)
        , c_(N * N * N * N, 0.)
        , a_(N * N * N, 0.)
      {}

      double &cubic(unsigned int n, unsigned int j, unsigned int k, unsigned int l)
      {
        sort3(j, k, l);
        return c_[((n * N_ + j) * N_ + k) * N_ + l];
      }
      double &quadratic(unsigned int n, unsigned int j, unsigned int k)
      {
        if (j > k)
          std::swap(j, k);
        return a_[(n * N_ + j) * N_ + k];
      }

      // The lists in the order of ReducedOrderModel::analytic_cubic_terms().
      void export_to(CubicFit &fit)
      {
        fit.cubic.clear();
        fit.quadratic.clear();
        for (unsigned int n = 0; n < N_; ++n)
          for (unsigned int j = 0; j < N_; ++j)
            for (unsigned int k = j; k < N_; ++k)
              {
                fit.quadratic.push_back({n, j, k, quadratic(n, j, k)});
                for (unsigned int l = k; l < N_; ++l)
                  fit.cubic.push_back({n, j, k, l, cubic(n, j, k, l)});
              }
      }

      static void sort3(unsigned int &j, unsigned int &k, unsigned int &l)
      {
        std::array<unsigned int, 3> s{{j, k, l}};
        std::sort(s.begin(), s.end());
        j = s[0];
        k = s[1];
        l = s[2];
      }

    private:
      unsigned int N_;
      std::vector<double> c_, a_;
    };

    void check_amplitudes(const Eigen::VectorXd &a, const char *who)
    {
      if (a.size() == 0)
        throw std::invalid_argument(std::string(who) + ": amplitudes is empty; need one a_j > 0 per mode");
      for (Eigen::Index j = 0; j < a.size(); ++j)
        if (!(a[j] > 0) || !std::isfinite(a[j]))
          {
            std::ostringstream s;
            s << who << ": amplitudes[" << j << "] = " << a[j] << " [m kg^1/2]; must be finite and > 0";
            throw std::invalid_argument(s.str());
          }
    }

    void check_finite(const Eigen::VectorXd &v, const Eigen::Index expected_size, const char *who, const Eigen::VectorXd &input)
    {
      bool ok = v.size() == expected_size;
      for (Eigen::Index i = 0; ok && i < v.size(); ++i)
        ok = std::isfinite(v[i]);
      if (!ok)
        {
          std::ostringstream s;
          s << who << ": the callback returned a vector of size " << v.size() << " (expected " << expected_size
            << ") or with non-finite entries, for the input " << input.transpose();
          throw std::runtime_error(s.str());
        }
    }
  } // namespace

  double CubicFit::cubic_coefficient(unsigned int n, unsigned int j, unsigned int k, unsigned int l) const
  {
    CubicTable::sort3(j, k, l);
    for (const auto &t : cubic)
      if (t.n == n && t.j == j && t.k == k && t.l == l)
        return t.value;
    throw std::out_of_range("CubicFit::cubic_coefficient: no term (" + std::to_string(n) + "," + std::to_string(j) +
                            "," + std::to_string(k) + "," + std::to_string(l) + ") for N = " +
                            std::to_string(n_modes()));
  }

  double CubicFit::quadratic_coefficient(unsigned int n, unsigned int j, unsigned int k) const
  {
    if (j > k)
      std::swap(j, k);
    for (const auto &t : quadratic)
      if (t.n == n && t.j == j && t.k == k)
        return t.value;
    throw std::out_of_range("CubicFit::quadratic_coefficient: no term (" + std::to_string(n) + "," +
                            std::to_string(j) + "," + std::to_string(k) + ") for N = " + std::to_string(n_modes()));
  }

  double CubicFit::max_abs_quadratic() const
  {
    double m = 0;
    for (const auto &t : quadratic)
      m = std::max(m, std::abs(t.value));
    return m;
  }

  Eigen::VectorXd step_amplitudes(const Eigen::VectorXd &max_abs_phi, const double length_scale)
  {
    if (!(length_scale > 0))
      throw std::invalid_argument("step_amplitudes: length_scale = " + std::to_string(length_scale) +
                                  " m; must be > 0 (e.g. the thickness h)");
    Eigen::VectorXd a(max_abs_phi.size());
    for (Eigen::Index j = 0; j < a.size(); ++j)
      {
        if (!(max_abs_phi[j] > 0))
          throw std::invalid_argument("step_amplitudes: max_abs_phi[" + std::to_string(j) +
                                      "] = " + std::to_string(max_abs_phi[j]) + " kg^-1/2; must be > 0");
        a[j] = length_scale / max_abs_phi[j];
      }
    return a;
  }

  // STEP. With g(q) = modal_force(q) − K_lin q and a single mode, pair or
  // triple prescribed, the even part of g(±q) holds only quadratic terms and the
  // odd part only cubic ones; the sign patterns then separate the individual
  // monomials (Muravyov & Rizzi 2003, Eqs. 9–14, with one amplitude per mode).
  CubicFit identify_cubic_step(const ModalForceFunction &modal_force, const StepSettings &settings)
  {
    const Eigen::VectorXd &a = settings.amplitudes;
    check_amplitudes(a, "identify_cubic_step");
    const unsigned int N = a.size();
    if (settings.linear_stiffness.size() != 0 &&
        (settings.linear_stiffness.rows() != N || settings.linear_stiffness.cols() != N))
      throw std::invalid_argument("identify_cubic_step: linear_stiffness is " +
                                  std::to_string(settings.linear_stiffness.rows()) + "×" +
                                  std::to_string(settings.linear_stiffness.cols()) + "; must be empty or " +
                                  std::to_string(N) + "×" + std::to_string(N));

    CubicFit fit;
    fit.amplitudes = a;
    fit.linear     = settings.linear_stiffness;

    auto g = [&](const Eigen::VectorXd &q) {
      Eigen::VectorXd f = modal_force(q);
      ++fit.n_evaluations;
      check_finite(f, N, "identify_cubic_step", q);
      if (settings.linear_stiffness.size() != 0)
        f -= settings.linear_stiffness * q;
      return f;
    };
    auto at = [&](std::initializer_list<std::pair<unsigned int, double>> entries) {
      Eigen::VectorXd q = Eigen::VectorXd::Zero(N);
      for (const auto &e : entries)
        q[e.first] = e.second * a[e.first];
      return q;
    };

    CubicTable table(N);
    // Single modes: g(±a_j e_j) = ± c_jjj a_j³ + a_jj a_j².
    for (unsigned int j = 0; j < N; ++j)
      {
        const Eigen::VectorXd gp = g(at({{j, +1.}})), gm = g(at({{j, -1.}}));
        for (unsigned int n = 0; n < N; ++n)
          {
            table.quadratic(n, j, j) = 0.5 * (gp[n] + gm[n]) / (a[j] * a[j]);
            table.cubic(n, j, j, j)  = 0.5 * (gp[n] - gm[n]) / (a[j] * a[j] * a[j]);
          }
      }
    // Pairs j < k: odd parts O1 (signs ++) and O2 (signs +−),
    //   O1 = c_jjj a_j³ + c_kkk a_k³ + c_jjk a_j² a_k + c_jkk a_j a_k²,
    //   O2 = c_jjj a_j³ − c_kkk a_k³ − c_jjk a_j² a_k + c_jkk a_j a_k²,
    // even parts E1 − E2 = 2 a_jk a_j a_k.
    for (unsigned int j = 0; j < N; ++j)
      for (unsigned int k = j + 1; k < N; ++k)
        {
          const Eigen::VectorXd gpp = g(at({{j, +1.}, {k, +1.}})), gmm = g(at({{j, -1.}, {k, -1.}}));
          const Eigen::VectorXd gpm = g(at({{j, +1.}, {k, -1.}})), gmp = g(at({{j, -1.}, {k, +1.}}));
          for (unsigned int n = 0; n < N; ++n)
            {
              const double O1 = 0.5 * (gpp[n] - gmm[n]), O2 = 0.5 * (gpm[n] - gmp[n]);
              const double E1 = 0.5 * (gpp[n] + gmm[n]), E2 = 0.5 * (gpm[n] + gmp[n]);
              const double cjjj = table.cubic(n, j, j, j), ckkk = table.cubic(n, k, k, k);
              table.cubic(n, j, j, k) = (0.5 * (O1 - O2) - ckkk * a[k] * a[k] * a[k]) / (a[j] * a[j] * a[k]);
              table.cubic(n, j, k, k) = (0.5 * (O1 + O2) - cjjj * a[j] * a[j] * a[j]) / (a[j] * a[k] * a[k]);
              table.quadratic(n, j, k) = (E1 - E2) / (2. * a[j] * a[k]);
            }
        }
    // Triples j < k < l: the odd part of g(±(a_j e_j + a_k e_k + a_l e_l)) is
    // the sum of all cubic monomials in (j,k,l); all but c_jkl are known now.
    for (unsigned int j = 0; j < N; ++j)
      for (unsigned int k = j + 1; k < N; ++k)
        for (unsigned int l = k + 1; l < N; ++l)
          {
            const Eigen::VectorXd gp = g(at({{j, +1.}, {k, +1.}, {l, +1.}}));
            const Eigen::VectorXd gm = g(at({{j, -1.}, {k, -1.}, {l, -1.}}));
            const std::array<unsigned int, 3> m{{j, k, l}};
            for (unsigned int n = 0; n < N; ++n)
              {
                double known = 0;
                for (unsigned int r = 0; r < 3; ++r)
                  for (unsigned int s = r; s < 3; ++s)
                    for (unsigned int t = s; t < 3; ++t)
                      if (!(r == 0 && s == 1 && t == 2))
                        known += table.cubic(n, m[r], m[s], m[t]) * a[m[r]] * a[m[s]] * a[m[t]];
                table.cubic(n, j, k, l) = (0.5 * (gp[n] - gm[n]) - known) / (a[j] * a[k] * a[l]);
              }
          }
    table.export_to(fit);
    fit.max_relative_response = 1;
    return fit;
  }

  // ICE. Each load case gives one sample (q, f̂); the model
  //   f̂_n = Σ_j K_nj q_j + Σ_{j≤k} a^(n)_jk q_j q_k + Σ_{j≤k≤l} c^(n)_jkl q_j q_k q_l
  // is linear in the coefficients, so all N equations share one regression
  // matrix. Its columns use the scaled coordinates q_j / a_j (all O(1)) so that
  // the least-squares problem is well conditioned whatever the modal units.
  CubicFit identify_cubic_ice(const ModalStaticSolveFunction &static_solve, const IceSettings &settings)
  {
    const Eigen::VectorXd &a = settings.amplitudes;
    check_amplitudes(a, "identify_cubic_ice");
    const unsigned int N = a.size();
    if (settings.omega.size() != N)
      throw std::invalid_argument("identify_cubic_ice: omega has " + std::to_string(settings.omega.size()) +
                                  " entries; must have one per mode (" + std::to_string(N) + ")");
    for (unsigned int n = 0; n < N; ++n)
      if (!(settings.omega[n] > 0))
        throw std::invalid_argument("identify_cubic_ice: omega[" + std::to_string(n) +
                                    "] = " + std::to_string(settings.omega[n]) + " rad/s; must be > 0");
    if (settings.load_levels.empty())
      throw std::invalid_argument("identify_cubic_ice: load_levels is empty; give at least one level > 0");
    for (const double level : settings.load_levels)
      if (!(level > 0))
        throw std::invalid_argument("identify_cubic_ice: load level " + std::to_string(level) +
                                    " (multiple of ω_j² a_j); must be > 0");

    // Load patterns: (modes, signs).
    std::vector<std::vector<std::pair<unsigned int, double>>> patterns;
    for (unsigned int j = 0; j < N; ++j)
      for (const double s : {1., -1.})
        patterns.push_back({{j, s}});
    if (settings.pairs)
      for (unsigned int j = 0; j < N; ++j)
        for (unsigned int k = j + 1; k < N; ++k)
          for (const double sj : {1., -1.})
            for (const double sk : {1., -1.})
              patterns.push_back({{j, sj}, {k, sk}});
    if (settings.triples)
      for (unsigned int j = 0; j < N; ++j)
        for (unsigned int k = j + 1; k < N; ++k)
          for (unsigned int l = k + 1; l < N; ++l)
            for (const double sj : {1., -1.})
              for (const double sk : {1., -1.})
                for (const double sl : {1., -1.})
                  patterns.push_back({{j, sj}, {k, sk}, {l, sl}});

    // Columns: linear, quadratic (j ≤ k), cubic (j ≤ k ≤ l).
    std::vector<std::array<unsigned int, 3>> monomials; // index 3 = N marks "absent"
    if (settings.fit_linear)
      for (unsigned int j = 0; j < N; ++j)
        monomials.push_back({{j, N, N}});
    if (settings.fit_quadratic)
      for (unsigned int j = 0; j < N; ++j)
        for (unsigned int k = j; k < N; ++k)
          monomials.push_back({{j, k, N}});
    for (unsigned int j = 0; j < N; ++j)
      for (unsigned int k = j; k < N; ++k)
        for (unsigned int l = k; l < N; ++l)
          monomials.push_back({{j, k, l}});

    const unsigned int n_samples = patterns.size() * settings.load_levels.size();
    if (n_samples < monomials.size())
      throw std::invalid_argument("identify_cubic_ice: " + std::to_string(n_samples) + " load cases for " +
                                  std::to_string(monomials.size()) +
                                  " coefficients per equation; enable pairs/triples or add load levels");

    CubicFit fit;
    fit.amplitudes = a;
    Eigen::MatrixXd A(n_samples, monomials.size());
    Eigen::MatrixXd B(n_samples, N);
    unsigned int row = 0;
    for (const double level : settings.load_levels)
      for (const auto &pattern : patterns)
        {
          Eigen::VectorXd f_hat = Eigen::VectorXd::Zero(N);
          for (const auto &e : pattern)
            f_hat[e.first] = e.second * level * settings.omega[e.first] * settings.omega[e.first] * a[e.first];
          const Eigen::VectorXd q = static_solve(f_hat);
          ++fit.n_evaluations;
          check_finite(q, N, "identify_cubic_ice", f_hat);
          const Eigen::ArrayXd y = q.array() / a.array();
          fit.max_relative_response = std::max(fit.max_relative_response, y.abs().maxCoeff());
          for (unsigned int c = 0; c < monomials.size(); ++c)
            {
              double v = 1;
              for (const unsigned int i : monomials[c])
                if (i < N)
                  v *= y[i];
              A(row, c) = v;
            }
          B.row(row) = f_hat.transpose();
          if (!settings.fit_linear)
            B.row(row) -= (settings.omega.array().square() * q.array()).matrix().transpose();
          ++row;
        }

    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
    if (qr.rank() < static_cast<Eigen::Index>(monomials.size()))
      throw std::runtime_error("identify_cubic_ice: the load cases give a rank-deficient fit (rank " +
                               std::to_string(qr.rank()) + " of " + std::to_string(monomials.size()) +
                               " columns); enable pairs/triples or add load levels");
    const Eigen::MatrixXd X = qr.solve(B);
    fit.relative_fit_residual = (A * X - B).norm() / B.norm();

    CubicTable table(N);
    fit.linear = settings.fit_linear ? Eigen::MatrixXd::Zero(N, N)
                                     : Eigen::MatrixXd(settings.omega.array().square().matrix().asDiagonal());
    for (unsigned int c = 0; c < monomials.size(); ++c)
      {
        const auto &m = monomials[c];
        double scale  = 1; // undo the column scaling q_j / a_j
        for (const unsigned int i : m)
          if (i < N)
            scale *= a[i];
        for (unsigned int n = 0; n < N; ++n)
          {
            const double value = X(c, n) / scale;
            if (m[1] == N)
              fit.linear(n, m[0]) = value;
            else if (m[2] == N)
              table.quadratic(n, m[0], m[1]) = value;
            else
              table.cubic(n, m[0], m[1], m[2]) = value;
          }
      }
    table.export_to(fit);
    return fit;
  }
} // namespace beamslider
