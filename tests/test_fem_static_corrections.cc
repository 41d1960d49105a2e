// Static corrections of the modal basis (fem/static_corrections.h) against
// what defines them: the enriched basis is mass-orthonormal and diagonalises
// K, keeps the modes as they are, and carries the FE's static deflection
// under a unit point load at each load position exactly (solved here by
// deal.II's sparse direct solver on the whole mesh), where the N modes alone
// miss part of it; and the scene parameter that puts them into the reduced
// model.
#include "fem/fe_beam.h"
#include "fem/fe_modes.h"
#include "fem/static_corrections.h"
#include "meshes/scene.h"
#include "reduced/rom_operator.h"
#include "verification/studies/fe_rom_study.h"

#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace beamslider;
using dealii::SparseMatrix;
using dealii::Vector;

namespace
{
  const std::string scene_dir = BEAMSLIDER_SOURCE_DIR "/meshes/";

  struct BeamMatrices
  {
    SparseMatrix<double> K, M;
  };

  void assemble(const FEBeam &beam, BeamMatrices &m)
  {
    beam.assemble_mass_matrix(m.M, beam.bending_constraints());
    beam.assemble_internal_force(Vector<double>(beam.n_dofs()), nullptr, &m.K, beam.bending_constraints());
  }

  // The consistent load vector of a unit transverse force at x.
  Vector<double> unit_load(const FEBeam &beam, const double x)
  {
    Vector<double> f(beam.n_dofs());
    const FEPointShape s = beam.point_shape(x);
    for (unsigned int a = 0; a < 4; ++a)
      if (!beam.bending_constraints().is_constrained(s.w_dofs[a]))
        f[s.w_dofs[a]] += s.w_values[a];
    return f;
  }

  // The static deflection a basis gives: Σ φ_n (φ_nᵀ f) / ω_n² (its Galerkin
  // solution, since the basis is M-orthonormal and K-diagonal).
  Vector<double> basis_solution(const FEModes &basis, const Vector<double> &f)
  {
    Vector<double> q(f.size());
    for (std::size_t n = 0; n < basis.shapes.size(); ++n)
      q.add((basis.shapes[n] * f) / (basis.omega[n] * basis.omega[n]), basis.shapes[n]);
    return q;
  }
} // namespace

TEST(StaticCorrections, BasisIsOrthonormalKeepsTheModesAndCarriesEachPointLoadExactly)
{
  const Scene scene = read_scene(scene_dir + "mueller2023.prm");
  const FEBeam beam(scene);
  BeamMatrices m;
  assemble(beam, m);
  dealii::SparseDirectUMFPACK K_inverse;
  K_inverse.initialize(m.K);

  const unsigned int N = 5, corrections = 4;
  const FEModes modes              = compute_bending_modes(beam, N);
  const std::vector<double> loads  = static_correction_positions(beam.length(), corrections);
  const FEModes enriched           = add_static_corrections(beam, modes, N, loads);
  ASSERT_EQ(enriched.shapes.size(), N + corrections);

  // The modes first and unchanged, the corrections above ω_N.
  for (unsigned int n = 0; n < N; ++n)
    {
      EXPECT_EQ(enriched.omega[n], modes.omega[n]);
      Vector<double> d = enriched.shapes[n];
      d -= modes.shapes[n];
      EXPECT_EQ(d.linfty_norm(), 0.);
    }
  for (unsigned int n = N; n < N + corrections; ++n)
    EXPECT_GT(enriched.omega[n], enriched.omega[n - 1]);

  // ΦᵀMΦ = I and ΦᵀKΦ = diag(ω²).
  Vector<double> Mx(beam.n_dofs()), Kx(beam.n_dofs());
  for (unsigned int i = 0; i < enriched.shapes.size(); ++i)
    {
      m.M.vmult(Mx, enriched.shapes[i]);
      m.K.vmult(Kx, enriched.shapes[i]);
      const double omega2 = enriched.omega[i] * enriched.omega[i];
      for (unsigned int j = 0; j < enriched.shapes.size(); ++j)
        {
          EXPECT_NEAR(enriched.shapes[j] * Mx, i == j ? 1. : 0., 1e-10) << i << ' ' << j;
          EXPECT_NEAR((enriched.shapes[j] * Kx) / omega2, i == j ? 1. : 0., 1e-10) << i << ' ' << j;
        }
    }

  // The static deflection under a unit load at each load position: exact in
  // the enriched basis, short of it with the modes alone.
  for (const double x : loads)
    {
      const Vector<double> f = unit_load(beam, x);
      Vector<double> exact(beam.n_dofs());
      K_inverse.vmult(exact, f);
      Vector<double> with = basis_solution(enriched, f), without = basis_solution(modes, f);
      with -= exact;
      without -= exact;
      EXPECT_LT(with.l2_norm(), 1e-9 * exact.l2_norm()) << "x = " << x;
      EXPECT_GT(without.l2_norm(), 1e-3 * exact.l2_norm()) << "x = " << x;
    }
}

// A load at a position given twice adds one correction, not two: the second
// is in the span of the first and is dropped.
TEST(StaticCorrections, ALoadGivenTwiceAddsOneCorrection)
{
  const Scene scene = read_scene(scene_dir + "mueller2023.prm");
  const FEBeam beam(scene);
  const FEModes modes    = compute_bending_modes(beam, 5);
  const FEModes enriched = add_static_corrections(beam, modes, 5, {0.3 * beam.length(), 0.3 * beam.length()});
  EXPECT_EQ(enriched.shapes.size(), 6u);
}

// The scene parameter reaches the reduced model: N modes and m corrections,
// the frequencies those of add_static_corrections, and the explicit step's
// stability limit set by the highest Ritz vector.
TEST(StaticCorrections, TheSceneParameterBuildsTheEnrichedReducedModel)
{
  Scene scene                               = read_scene(scene_dir + "mueller2023.prm");
  scene.discretisation.n_static_corrections = 4;
  ModelSetting setting                      = scene_model(scene, "rom");
  EXPECT_EQ(setting.n_static_corrections, 4u);
  EXPECT_NE(setting.label().find("N=5+4sc"), std::string::npos) << setting.label();
  EXPECT_EQ(scene_model(scene, "fe").n_static_corrections, 0u);

  const ReducedOrderModel rom = make_reduced_model(scene, setting);
  const FEBeam beam(scene);
  const FEModes enriched = add_static_corrections(beam, compute_bending_modes(beam, 5), 5,
                                                  static_correction_positions(beam.length(), 4));
  ASSERT_EQ(rom.n_modes(), enriched.omega.size());
  for (unsigned int n = 0; n < rom.n_modes(); ++n)
    EXPECT_DOUBLE_EQ(rom.basis().omega[n], enriched.omega[n]);

  setting.time_step = 1.01 * 2. / enriched.omega.back();
  EXPECT_THROW(require_stable_time_step(setting, *make_beam_model(scene, setting)), InputError);
}
