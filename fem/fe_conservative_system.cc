#include "fem/fe_conservative_system.h"

#include <deal.II/lac/sparse_matrix.h>

#include <memory>

namespace beamslider
{
  using namespace dealii;

  namespace
  {
    Eigen::MatrixXd dense_on(const SparseMatrix<double> &A, const std::vector<unsigned int> &dofs,
                             const std::vector<int> &row_of)
    {
      Eigen::MatrixXd D = Eigen::MatrixXd::Zero(dofs.size(), dofs.size());
      for (unsigned int r = 0; r < dofs.size(); ++r)
        for (auto it = A.begin(dofs[r]); it != A.end(dofs[r]); ++it)
          if (row_of[it->column()] >= 0)
            D(r, row_of[it->column()]) = it->value();
      return D;
    }
  } // namespace

  Eigen::VectorXd FEConservativeSystem::deflection_at(const double x) const
  {
    const FEPointShape s = beam->point_shape(x);
    Eigen::VectorXd c    = Eigen::VectorXd::Zero(free_dofs.size());
    for (unsigned int r = 0; r < free_dofs.size(); ++r)
      for (unsigned int a = 0; a < 4; ++a)
        if (free_dofs[r] == s.w_dofs[a])
          c[r] += s.w_values[a];
    return c;
  }

  std::vector<bool> FEConservativeSystem::even_harmonic_dofs() const
  {
    std::vector<bool> even(free_dofs.size());
    for (unsigned int r = 0; r < free_dofs.size(); ++r)
      even[r] = beam->axial_dofs()[free_dofs[r]];
    return even;
  }

  FEConservativeSystem make_fe_conservative_system(const FEBeam &beam)
  {
    FEConservativeSystem fe;
    fe.beam = &beam;
    auto row_of = std::make_shared<std::vector<int>>(beam.n_dofs(), -1);
    for (unsigned int i = 0; i < beam.n_dofs(); ++i)
      if (!beam.constraints().is_constrained(i))
        {
          (*row_of)[i] = fe.free_dofs.size();
          fe.free_dofs.push_back(i);
        }

    SparseMatrix<double> M, K;
    beam.assemble_mass_matrix(M, beam.constraints());
    beam.assemble_internal_force(Vector<double>(beam.n_dofs()), nullptr, &K, beam.constraints());
    fe.system.mass      = dense_on(M, fe.free_dofs, *row_of);
    fe.system.stiffness = dense_on(K, fe.free_dofs, *row_of);

    const auto dofs   = fe.free_dofs;
    const Eigen::MatrixXd K_lin = fe.system.stiffness;
    auto scatter = [dofs, &beam](const Eigen::VectorXd &q) {
      Vector<double> x(beam.n_dofs());
      for (unsigned int r = 0; r < dofs.size(); ++r)
        x[dofs[r]] = q[r];
      return x;
    };
    fe.system.force = [scatter, dofs, K_lin, &beam](const Eigen::VectorXd &q) {
      Vector<double> f;
      beam.assemble_internal_force(scatter(q), &f, nullptr, beam.constraints());
      Eigen::VectorXd g(dofs.size());
      for (unsigned int r = 0; r < dofs.size(); ++r)
        g[r] = f[dofs[r]];
      return Eigen::VectorXd(g - K_lin * q);
    };
    fe.system.tangent = [scatter, dofs, K_lin, row_of, &beam](const Eigen::VectorXd &q) {
      SparseMatrix<double> K_t;
      beam.assemble_internal_force(scatter(q), nullptr, &K_t, beam.constraints());
      return Eigen::MatrixXd(dense_on(K_t, dofs, *row_of) - K_lin);
    };
    return fe;
  }

  Backbone compute_fe_backbone(const FEConservativeSystem &fe, const BeamBackboneSettings &settings)
  {
    BackboneSettings s       = make_beam_backbone_settings(fe.deflection_at(0.5 * fe.beam->length()), settings);
    s.hb.even_harmonic_dofs  = fe.even_harmonic_dofs();
    return compute_backbone(fe.system, s);
  }
} // namespace beamslider
