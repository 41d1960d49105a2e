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
#include "scene/scene.h"
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
  // ΦᵀMΦ = I and ΦᵀKΦ = diag(ω²): the basis is "modal".
  void expect_modal(const BeamMatrices &m, const FEModes &basis)
  {
    Vector<double> Mx(basis.shapes.front().size()), Kx(basis.shapes.front().size());
    for (unsigned int i = 0; i < basis.shapes.size(); ++i)
      {
        m.M.vmult(Mx, basis.shapes[i]);
        m.K.vmult(Kx, basis.shapes[i]);
        const double omega2 = basis.omega[i] * basis.omega[i];
        for (unsigned int j = 0; j < basis.shapes.size(); ++j)
          {
            EXPECT_NEAR(basis.shapes[j] * Mx, i == j ? 1. : 0., 1e-10) << i << ' ' << j;
            EXPECT_NEAR((basis.shapes[j] * Kx) / omega2, i == j ? 1. : 0., 1e-10) << i << ' ' << j;
          }
      }
  }

  // The part of x outside span(basis), by M-orthogonal projection, relative
  // to x's M-norm.
  double outside_span(const BeamMatrices &m, const FEModes &basis, const Vector<double> &x)
  {
    Vector<double> Mx(x.size()), rest = x;
    m.M.vmult(Mx, x);
    for (const Vector<double> &phi : basis.shapes)
      rest.add(-(phi * Mx), phi);
    Vector<double> Mrest(x.size());
    m.M.vmult(Mrest, rest);
    return std::sqrt((rest * Mrest) / (x * Mx));
  }
  // The mueller2023 beam with its K and M and a direct solver for K.
  struct MuellerBeam
  {
    MuellerBeam()
      : beam(read_scene(scene_dir + "mueller2023.prm"))
    {
      assemble(beam, m);
      K_inverse.initialize(m.K);
    }
    const FEBeam beam;
    BeamMatrices m;
    dealii::SparseDirectUMFPACK K_inverse;
  };
} // namespace

TEST(StaticCorrections, BasisIsOrthonormalKeepsTheModesAndCarriesEachPointLoadExactly)
{
  const MuellerBeam mueller;
  const auto &[beam, m, K_inverse] = mueller;

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

  expect_modal(m, enriched);

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

// Load-dependent Ritz blocks (Wilson, Yuan & Dickens): with b = 2 the basis
// is still modal with the modes unchanged, and it holds the second Krylov
// block K⁻¹M ψ_k of every static correction ψ_k (computed here with
// deal.II's sparse direct solver), which the corrections alone do not; the
// span grows, so its lowest Ritz frequency comes down toward ω_{N+1} and
// stays above it (Courant–Fischer).
TEST(StaticCorrections, RitzBlocksHoldTheNextKrylovBlockAndApproachTheFirstMissingMode)
{
  const MuellerBeam mueller;
  const auto &[beam, m, K_inverse] = mueller;

  const unsigned int N = 5, corrections = 2;
  const FEModes modes             = compute_bending_modes(beam, N + 1);
  const std::vector<double> loads = static_correction_positions(beam.length(), corrections);
  const FEModes one = add_static_corrections(beam, modes, N, loads, 1);
  const FEModes two = add_static_corrections(beam, modes, N, loads, 2);
  ASSERT_EQ(two.shapes.size(), N + 2 * corrections);
  for (unsigned int n = 0; n < N; ++n)
    EXPECT_EQ(two.omega[n], modes.omega[n]);
  expect_modal(m, two);

  for (const double x : loads)
    {
      // ψ = K⁻¹f − Σ φ_n φ_nᵀ f / ω_n², then y = K⁻¹Mψ.
      const Vector<double> f = unit_load(beam, x);
      Vector<double> psi(beam.n_dofs()), Mpsi(beam.n_dofs()), y(beam.n_dofs());
      K_inverse.vmult(psi, f);
      for (unsigned int n = 0; n < N; ++n)
        psi.add(-(modes.shapes[n] * f) / (modes.omega[n] * modes.omega[n]), modes.shapes[n]);
      m.M.vmult(Mpsi, psi);
      K_inverse.vmult(y, Mpsi);
      EXPECT_LT(outside_span(m, one, psi), 1e-9) << "x = " << x;
      EXPECT_LT(outside_span(m, two, y), 1e-8) << "x = " << x;
      EXPECT_GT(outside_span(m, one, y), 1e-4) << "x = " << x;
    }
  const double omega_missing = modes.omega[N];
  EXPECT_GE(one.omega[N], omega_missing * (1 - 1e-12));
  EXPECT_GE(two.omega[N], omega_missing * (1 - 1e-12));
  EXPECT_LT(two.omega[N] - omega_missing, one.omega[N] - omega_missing);
}

// The scene parameter: the reduced model of N modes, m corrections and b
// blocks has N + b·m coordinates and is labelled so; blocks without
// corrections are refused, naming the parameter.
TEST(StaticCorrections, TheRitzBlocksParameterReachesTheReducedModel)
{
  Scene scene                               = read_scene(scene_dir + "mueller2023.prm");
  scene.discretisation.n_static_corrections = 2;
  scene.discretisation.ritz_blocks          = 3;
  const ModelSetting setting                = scene_model(scene, "rom");
  EXPECT_EQ(setting.ritz_blocks, 3u);
  EXPECT_NE(setting.label().find("N=5+2sc+4ldr"), std::string::npos) << setting.label();
  EXPECT_EQ(make_reduced_model(scene, setting).n_modes(), 5u + 3u * 2u);

  scene.discretisation.n_static_corrections = 0;
  try
    {
      validate_scene(scene);
      FAIL() << "Ritz blocks without static corrections accepted";
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find("Discretisation/Ritz blocks"), std::string::npos) << e.what();
    }
}
