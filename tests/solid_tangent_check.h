// The tangent of a solid model against its internal force: f is exactly cubic
// in u, so the central difference D(ε) = K v + ε² c and the Richardson
// combination (4 D(ε) − D(2ε)) / 3 = K v without truncation error, at a step
// large enough for round-off not to matter. Used by the solid tests.
#pragma once

#include "fem/solid_model.h"

#include <random>

namespace beamslider::testing
{
  // ‖(4 D(0.1) − D(0.2))/3 − K_t(u) v‖ / ‖K_t(u) v‖ at a random state u
  // (0.5 mm per DoF) along a random direction v, the clamped DoFs at zero.
  template <int dim>
  double tangent_defect(const SolidModel<dim> &model, const unsigned int seed)
  {
    using dealii::PETScWrappers::MPI::SparseMatrix;
    using dealii::PETScWrappers::MPI::Vector;
    Vector u, v, u_ghost, Kv;
    model.reinit_vector(u);
    model.reinit_vector(v);
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> unit(-1, 1);
    for (const auto i : model.locally_owned_dofs())
      {
        u[i] = model.constraints().is_constrained(i) ? 0. : 0.5e-3 * unit(random);
        v[i] = model.constraints().is_constrained(i) ? 0. : 1e-3 * unit(random);
      }
    u.compress(dealii::VectorOperation::insert);
    v.compress(dealii::VectorOperation::insert);
    model.distribute(u);
    model.distribute(v);
    SparseMatrix K;
    model.reinit_ghosted_vector(u_ghost);
    u_ghost = u;
    model.assemble_internal_force(u_ghost, nullptr, &K);
    model.reinit_vector(Kv);
    K.vmult(Kv, v);
    // Constrained rows of K hold a filler diagonal, of f nothing: compare
    // the free rows (an elastic end's face DoFs are not zero in v).
    model.constraints().set_zero(Kv);
    auto central_difference = [&](const double eps) {
      Vector f_plus, f_minus;
      for (const double sign : {1., -1.})
        {
          Vector w = u;
          w.add(sign * eps, v);
          u_ghost = w;
          model.assemble_internal_force(u_ghost, sign > 0 ? &f_plus : &f_minus, nullptr);
        }
      f_plus -= f_minus;
      f_plus /= 2 * eps;
      return f_plus;
    };
    Vector difference = central_difference(0.1);
    difference *= 4. / 3;
    difference.add(-1. / 3, central_difference(0.2));
    difference -= Kv;
    return difference.l2_norm() / Kv.l2_norm();
  }
} // namespace beamslider::testing
