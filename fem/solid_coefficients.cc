#include "fem/solid_coefficients.h"

#include "numerics/newton.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <algorithm>
#include <array>
#include <sstream>
#include <stdexcept>

namespace beamslider
{
  using namespace dealii;

  template <int dim>
  SolidModalCoefficients<dim>::SolidModalCoefficients(const SolidModel<dim> &model, const SolidModes &modes,
                                                      const unsigned int n_modes)
    : SolidModalCoefficients(model, modes,
                             std::vector<unsigned int>(modes.bending.begin(),
                                                       modes.bending.begin() +
                                                         std::min<std::size_t>(n_modes, modes.bending.size())))
  {
    if (n_modes > modes.bending.size())
      throw std::invalid_argument("SolidModalCoefficients: " + std::to_string(n_modes) + " modes asked, " +
                                  std::to_string(modes.bending.size()) + " bending modes computed");
  }

  template <int dim>
  SolidModalCoefficients<dim>::SolidModalCoefficients(const SolidModel<dim> &model, const SolidModes &modes,
                                                      const std::vector<unsigned int> &indices)
    : model(model)
    , statics(model)
  {
    for (const unsigned int i : indices)
      {
        if (i >= modes.all.size())
          throw std::invalid_argument("SolidModalCoefficients: mode " + std::to_string(i + 1) + " asked, " +
                                      std::to_string(modes.all.size()) + " modes computed");
        const SolidMode &mode = modes.all[i];
        Phi.emplace_back();
        model.reinit_vector(Phi.back());
        Phi.back() = mode.vector;
        Phi_ghosted.push_back(&mode.vector);
        omegas.push_back(mode.omega);
      }
    model.assemble_mass_matrix(M);
  }

  template <int dim>
  Eigen::VectorXd SolidModalCoefficients<dim>::omega() const
  {
    return Eigen::Map<const Eigen::VectorXd>(omegas.data(), omegas.size());
  }

  template <int dim>
  Eigen::VectorXd SolidModalCoefficients<dim>::amplitudes(const double length) const
  {
    Eigen::VectorXd a(Phi.size());
    for (unsigned int j = 0; j < Phi.size(); ++j)
      a[j] = length / Phi[j].linfty_norm();
    return a;
  }

  template <int dim>
  CubicFit SolidModalCoefficients<dim>::exact_polynomial() const
  {
    const unsigned int N = Phi.size();
    const auto &fe       = model.get_dof_handler().get_fe();
    const Quadrature<dim> &quadrature = model.quadrature();
    FEValues<dim> fe_values(model.mapping(), fe, quadrature, update_gradients | update_JxW_values);
    const FEValuesExtractors::Vector displacement(0);
    const double factor    = model.out_of_plane_thickness();
    const Tensor<2, dim> I = unit_symmetric_tensor<dim>();
    double lambda = 0, mu = 0; // of the current cell's region
    auto C        = [&](const Tensor<2, dim> &X) { return lambda * trace(X) * I + 2 * mu * X; };

    // Integrals per (n, j), (n, j, k), (n, j, k, l), unsymmetrised, in one flat array.
    std::vector<double> K(N * N, 0.), Q(N * N * N, 0.), B(N * N * N * N, 0.);
    std::vector<std::vector<Tensor<2, dim>>> G(N, std::vector<Tensor<2, dim>>(quadrature.size()));
    std::vector<Tensor<2, dim>> e(N), Ce(N);
    std::vector<Tensor<2, dim>> H(N * N), CH(N * N);
    for (const auto &cell : model.get_dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          lambda = model.material(cell->material_id()).lambda;
          mu     = model.material(cell->material_id()).mu;
          fe_values.reinit(cell);
          for (unsigned int j = 0; j < N; ++j)
            fe_values[displacement].get_function_gradients(*Phi_ghosted[j], G[j]);
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              const double JxW = fe_values.JxW(q) * factor;
              for (unsigned int j = 0; j < N; ++j)
                {
                  e[j]  = symmetrize(G[j][q]);
                  Ce[j] = C(e[j]);
                  for (unsigned int k = 0; k < N; ++k)
                    {
                      H[j * N + k]  = 0.5 * (transpose(G[j][q]) * G[k][q] + transpose(G[k][q]) * G[j][q]);
                      CH[j * N + k] = C(H[j * N + k]);
                    }
                }
              for (unsigned int n = 0; n < N; ++n)
                for (unsigned int j = 0; j < N; ++j)
                  {
                    K[n * N + j] += scalar_product(e[n], Ce[j]) * JxW;
                    for (unsigned int k = 0; k < N; ++k)
                      {
                        Q[(n * N + j) * N + k] +=
                          (0.5 * scalar_product(CH[j * N + k], e[n]) + scalar_product(Ce[j], H[k * N + n])) * JxW;
                        for (unsigned int l = 0; l < N; ++l)
                          B[((n * N + j) * N + k) * N + l] += 0.5 * scalar_product(CH[j * N + k], H[l * N + n]) * JxW;
                      }
                  }
            }
        }
    const MPI_Comm comm = model.communicator();
    Utilities::MPI::sum(K, comm, K);
    Utilities::MPI::sum(Q, comm, Q);
    Utilities::MPI::sum(B, comm, B);

    // The elastic supports' springs (linear: they add to K only).
    if (model.elastic_supports())
      for (unsigned int n = 0; n < N; ++n)
        for (unsigned int j = 0; j < N; ++j)
          K[n * N + j] += model.support_spring_product(*Phi_ghosted[n], *Phi_ghosted[j]);

    CubicFit fit;
    fit.linear = Eigen::Map<const Eigen::MatrixXd>(K.data(), N, N).transpose();
    fit.amplitudes = Eigen::VectorXd::Zero(N);
    fit.max_relative_response = 1;
    for (unsigned int n = 0; n < N; ++n)
      for (unsigned int j = 0; j < N; ++j)
        for (unsigned int k = j; k < N; ++k)
          fit.quadratic.push_back(
            {n, j, k, Q[(n * N + j) * N + k] + (j == k ? 0. : Q[(n * N + k) * N + j])});
    for (unsigned int n = 0; n < N; ++n)
      for (unsigned int j = 0; j < N; ++j)
        for (unsigned int k = j; k < N; ++k)
          for (unsigned int l = k; l < N; ++l)
            {
              std::array<unsigned int, 3> idx{{j, k, l}};
              double value = 0;
              do
                value += B[((n * N + idx[0]) * N + idx[1]) * N + idx[2]];
              while (std::next_permutation(idx.begin(), idx.end()));
              fit.cubic.push_back({n, j, k, l, value});
            }
    return fit;
  }

  template <int dim>
  Eigen::VectorXd SolidModalCoefficients<dim>::modal_force(const Eigen::VectorXd &q) const
  {
    PETScWrappers::MPI::Vector u, u_ghosted, f;
    model.reinit_vector(u);
    for (unsigned int j = 0; j < Phi.size(); ++j)
      u.add(q[j], Phi[j]);
    model.reinit_ghosted_vector(u_ghosted);
    u_ghosted = u;
    model.assemble_internal_force(u_ghosted, &f, nullptr);
    Eigen::VectorXd p(Phi.size());
    for (unsigned int n = 0; n < Phi.size(); ++n)
      p[n] = Phi[n] * f;
    return p;
  }

  // Relaxed STEP at one q as numerics/newton.h's problem: full Newton on
  // f(Φq + v) = M Φ λ with Φᵀ M v = 0, for v and the holding forces λ.
  template <int dim>
  struct SolidModalCoefficients<dim>::RelaxedStep
  {
    SolidModalCoefficients<dim> &c;
    const unsigned int N;
    std::vector<PETScWrappers::MPI::Vector> MPhi, B; // M Φ_j on the free DoFs; K⁻¹ M Φ_j
    PETScWrappers::MPI::Vector u, u_ghosted, f, residual, a, dv;
    PETScWrappers::MPI::SparseMatrix K;
    Eigen::VectorXd lambda;
    double q_norm = 0;

    RelaxedStep(SolidModalCoefficients<dim> &c, const Eigen::VectorXd &q)
      : c(c)
      , N(c.Phi.size())
      , MPhi(N)
      , B(N)
    {
      // M Φ_j on the free DoFs: the directions the holding forces act in.
      for (unsigned int j = 0; j < N; ++j)
        {
          c.model.reinit_vector(MPhi[j]);
          c.model.reinit_vector(B[j]);
          c.M.vmult(MPhi[j], c.Phi[j]);
          c.model.constraints().set_zero(MPhi[j]);
        }
      c.model.reinit_vector(u);
      c.model.reinit_vector(a);
      c.model.reinit_vector(dv);
      c.model.reinit_ghosted_vector(u_ghosted);
      for (unsigned int j = 0; j < N; ++j)
        u.add(q[j], c.Phi[j]);
      q_norm = u.l2_norm();
      // Start from plain STEP: v = 0, λ = Φᵀ f(Φ q).
      lambda = c.modal_force(q);
    }

    NewtonState evaluate(bool)
    {
      u_ghosted = u;
      c.model.assemble_internal_force(u_ghosted, &f, &K);
      residual = f;
      for (unsigned int j = 0; j < N; ++j)
        residual.add(-lambda[j], MPhi[j]); // f(u) − M Φ λ
      return NewtonState::go_on;
    }

    double relative_residual() const { return residual.l2_norm() / std::max(f.l2_norm(), 1e-300); }

    void factorise() { c.relaxed_tangent.factorise(K); }

    double correct()
    {
      // dv = a + B dλ with a = −K⁻¹ r, B_j = K⁻¹ M Φ_j; (MΦ)ᵀ dv = 0 gives S dλ = −(MΦ)ᵀ a.
      residual *= -1.;
      c.relaxed_tangent.solve(a, residual);
      Eigen::MatrixXd S(N, N);
      Eigen::VectorXd rhs(N);
      for (unsigned int j = 0; j < N; ++j)
        c.relaxed_tangent.solve(B[j], MPhi[j]);
      for (unsigned int i = 0; i < N; ++i)
        {
          rhs[i] = -(MPhi[i] * a);
          for (unsigned int j = 0; j < N; ++j)
            S(i, j) = MPhi[i] * B[j];
        }
      const Eigen::VectorXd dlambda = S.lu().solve(rhs);
      dv = a;
      for (unsigned int j = 0; j < N; ++j)
        dv.add(dlambda[j], B[j]);
      c.model.constraints().set_zero(dv);
      u += dv;
      c.model.distribute(u);
      lambda += dlambda;
      return dv.l2_norm();
    }

    bool small(const double correction) const { return correction < 1e-12 * q_norm; }
  };

  template <int dim>
  Eigen::VectorXd SolidModalCoefficients<dim>::modal_force_relaxed(const Eigen::VectorXd &q)
  {
    RelaxedStep step(*this, q);
    NewtonControl control;
    control.max_iterations = 30;
    const NewtonOutcome outcome = solve_newton(step, control);
    if (outcome.converged())
      return step.lambda;
    step.evaluate(false); // the residual where it stopped
    throw SolidStaticSolveError("relaxed STEP did not converge at |q| = " + std::to_string(q.norm()) +
                                ": relative residual " + std::to_string(step.relative_residual()) + " after " +
                                std::to_string(outcome.iterations) + " Newton iterations (" + outcome.reason() + ")");
  }

  template <int dim>
  PETScWrappers::MPI::Vector SolidModalCoefficients<dim>::modal_load(const Eigen::VectorXd &f_hat) const
  {
    PETScWrappers::MPI::Vector load, F;
    model.reinit_vector(load);
    model.reinit_vector(F);
    for (unsigned int j = 0; j < Phi.size(); ++j)
      load.add(f_hat[j], Phi[j]);
    M.vmult(F, load);
    model.constraints().set_zero(F); // Φ is zero there; M's diagonal filler is not a load
    return F;
  }

  template <int dim>
  Eigen::VectorXd SolidModalCoefficients<dim>::modal_coordinates(const PETScWrappers::MPI::Vector &u) const
  {
    PETScWrappers::MPI::Vector free_part, Mu;
    model.reinit_vector(free_part);
    model.reinit_vector(Mu);
    free_part = u;
    model.constraints().set_zero(free_part); // M's filler diagonal is no mass
    M.vmult(Mu, free_part);
    Eigen::VectorXd q(Phi.size());
    for (unsigned int n = 0; n < Phi.size(); ++n)
      q[n] = Phi[n] * Mu;
    return q;
  }

  template <int dim>
  Eigen::VectorXd SolidModalCoefficients<dim>::modal_static_response(const Eigen::VectorXd &f_hat)
  {
    PETScWrappers::MPI::Vector u;
    model.reinit_vector(u);
    statics.solve(modal_load(f_hat), u);
    return modal_coordinates(u);
  }

  template <int dim>
  CubicFit solid_cubic_fit(SolidModalCoefficients<dim> &coefficients, const std::string &method,
                           const double thickness)
  {
    const Eigen::VectorXd omega = coefficients.omega();
    if (method == "exact")
      return coefficients.exact_polynomial();
    if (method == "step")
      return identify_cubic_step([&](const Eigen::VectorXd &q) { return coefficients.modal_force(q); },
                                 {coefficients.amplitudes(thickness), omega.array().square().matrix().asDiagonal()});
    // Relaxed STEP is not exactly cubic (the relaxed DoFs include the other
    // bending modes, which add q^5 and higher terms): fitted at 0.03 h as ICE
    // is. Measured on the plane-stress strip, N = 2: b_111 at amplitudes of
    // 1 / 0.3 / 0.1 / 0.03 h: -4.1 / -0.44 / -0.033 / +0.014 % from ICE.
    const double relaxed_amplitude = 0.03;
    if (method == "step-relaxed")
      return identify_cubic_step([&](const Eigen::VectorXd &q) { return coefficients.modal_force_relaxed(q); },
                                 {coefficients.amplitudes(relaxed_amplitude * thickness),
                                  omega.array().square().matrix().asDiagonal()});
    if (method == "ice")
      {
        IceSettings ice;
        ice.omega      = omega;
        ice.amplitudes = coefficients.amplitudes(0.03 * thickness);
        return identify_cubic_ice(
          [&](const Eigen::VectorXd &f_hat) { return coefficients.modal_static_response(f_hat); }, ice);
      }
    throw std::invalid_argument("solid_cubic_fit: method '" + method + "' is not one of exact, step, step-relaxed, ice");
  }

  template class SolidModalCoefficients<2>;
  template class SolidModalCoefficients<3>;
  template CubicFit solid_cubic_fit(SolidModalCoefficients<2> &, const std::string &, double);
  template CubicFit solid_cubic_fit(SolidModalCoefficients<3> &, const std::string &, double);
} // namespace beamslider
