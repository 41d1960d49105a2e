// Google Benchmark timings of the costly parts, on the default scene
// (mueller2023), one core. Not part of the test suite; run
//
//   build/verification/beamslider_benchmarks [--benchmark_filter=Rom]
//
// Each benchmark reports the rate that matters to a user next to the raw
// time: time steps per second for the contact runs (and simulated seconds
// per wall second), backbone points for harmonic balance.
#include "runs/adaptation_run.h"
#include "fem/fe_beam.h"
#include "fem/fe_beam_system.h"
#include "fem/fe_modal_basis.h"
#include "fem/fe_modes.h"
#include "fem/fe_transient.h"
#include "fem/static_corrections.h"
#include "fem/solid_model.h"
#include "scene/scene.h"
#include "reduced/beam_backbone.h"
#include "reduced/rom_beam_system.h"
#include "reduced/rom_implicit_beam_system.h"
#include "numerics/elapsed.h"
#include "verification/benchmarks/heap_counter.h"
#include "verification/report/report.h"
#include "verification/studies/coefficient_methods.h"

#include <deal.II/base/mpi.h>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <memory>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

using namespace beamslider;

namespace
{
  const Scene &default_scene()
  {
    static const Scene scene = read_scene(BEAMSLIDER_SOURCE_DIR "/meshes/mueller2023.prm");
    return scene;
  }

  // Runs `run` to t_end in chunks of `chunk` simulated seconds and returns
  // the fastest chunk's wall time per step [µs]: this sandbox's timings
  // come in bursts of ±40 % (other machines' load), and the fastest tenth of
  // a window is what the code costs when it has the core. The whole
  // window's mean stays beside it as us/step.
  double run_in_chunks(AdaptationRun &run, const double t_end, const double chunk, const double dt,
                       RunResult &result)
  {
    double fastest = std::numeric_limits<double>::infinity();
    result         = RunResult();
    result.status  = RunStatus::completed;
    for (double t = run.stepper().state().t; t + 0.5 * dt < t_end && result.status == RunStatus::completed;)
      {
        const double next = std::min(t + chunk, t_end);
        const auto start  = std::chrono::steady_clock::now();
        const RunResult r = run.run_until(next);
        const double wall = elapsed_seconds(start);
        if (r.n_steps > 0)
          fastest = std::min(fastest, 1e6 * wall / r.n_steps);
        result.status = r.status;
        result.message = r.message;
        result.n_steps += r.n_steps;
        result.n_contact_steps += r.n_contact_steps;
        result.solver_iterations += r.solver_iterations;
        result.slider_x_over_L = r.slider_x_over_L;
        t = run.stepper().state().t;
      }
    return fastest;
  }

  // The signature-move run (124 Hz, 14 m/s², x_C/L = 0.3) for `seconds` of
  // simulated time on `beam` at the scene's Δt, counting steps, contact
  // solves and the heap allocations of the stepping after the first 0.5 s
  // (scratch sizes settled; trace rows and period records included).
  void run_contact(benchmark::State &state, const Scene &scene, BeamSystem &beam, const double seconds,
                   const double time_step)
  {
    RunOptions options        = RunOptions::from_scene(scene, time_step);
    options.end_time          = seconds;
    options.output_rate       = 1000.;
    options.progress_interval = 1e300;
    unsigned long steps = 0, contact_steps = 0, iterations = 0, allocations = 0, counted_steps = 0;
    double wall = 0, fastest = 0;
    for (auto _ : state)
      {
        const auto start = std::chrono::steady_clock::now();
        AdaptationRun run(scene, beam, options);
        run.on_trace_row      = [](const TraceRow &row) { benchmark::DoNotOptimize(row.w_center); };
        const RunResult first = run.run_until(0.5);
        heap_counter::start();
        RunResult rest;
        fastest = run_in_chunks(run, seconds, 0.1, time_step, rest);
        allocations += heap_counter::stop();
        wall += elapsed_seconds(start);
        for (const RunResult *r : {&first, static_cast<const RunResult *>(&rest)})
          {
            if (r->status != RunStatus::completed)
              state.SkipWithError(r->message.c_str());
            steps += r->n_steps;
            contact_steps += r->n_contact_steps;
            iterations += r->solver_iterations;
          }
        counted_steps += rest.n_steps;
      }
    state.counters["us/step"]             = 1e6 * wall / std::max<unsigned long>(steps, 1);
    state.counters["us/step fastest"]     = fastest;
    state.counters["simulated s/s"]       = steps * time_step / std::max(wall, 1e-300);
    state.counters["contact solves/step"] = double(contact_steps) / std::max<unsigned long>(steps, 1);
    state.counters["sweeps/solve"]        = double(iterations) / std::max<unsigned long>(contact_steps, 1);
    state.counters["allocations/step"]    = double(allocations) / std::max<unsigned long>(counted_steps, 1);
  }
} // namespace

// ROM with contact, N modes from the FE basis, analytic coefficients, the
// first 10 s (slider at rest at first, the jump near 5 s: both regimes), at
// the scene's Δt or, where the explicit step needs less (N = 10), at the
// largest step of the form Δt/2^k below 2/ω_N.
static void RomContact(benchmark::State &state)
{
  Scene scene                      = default_scene();
  scene.discretisation.n_modes     = state.range(0);
  const FEBeam fe(scene);
  RomBeamSystem rom = RomBeamSystem::from_scene(
    scene, make_modal_basis(fe, compute_bending_modes(fe, scene.discretisation.n_modes), scene.discretisation.n_modes));
  double dt = scene.time_stepping.time_step;
  while (dt > rom.max_stable_time_step())
    dt /= 2;
  state.counters["dt [us]"] = 1e6 * dt;
  run_contact(state, scene, rom, 10.0, dt);
}
BENCHMARK(RomContact)->Arg(5)->Arg(7)->Arg(10)->Arg(15)->Arg(20)->Arg(30)->Unit(benchmark::kSecond)->Iterations(1);

// The same with N modes and m static corrections (fem/static_corrections.h;
// the candidates of the speed–accuracy front, `ladder --full`): the same
// explicit step on N + m coordinates, at the largest Δt/2^k its stiffest
// Ritz vector allows.
static void RomContactCorrected(benchmark::State &state)
{
  Scene scene                                = default_scene();
  scene.discretisation.n_modes               = state.range(0);
  scene.discretisation.n_static_corrections = state.range(1);
  const FEBeam fe(scene);
  const FEModes enriched = add_static_corrections(
    fe, compute_bending_modes(fe, scene.discretisation.n_modes), scene.discretisation.n_modes,
    static_correction_positions(fe.length(), scene.discretisation.n_static_corrections));
  RomBeamSystem rom = RomBeamSystem::from_scene(scene, make_modal_basis(fe, enriched));
  double dt         = scene.time_stepping.time_step;
  while (dt > rom.max_stable_time_step())
    dt /= 2;
  state.counters["dt [us]"] = 1e6 * dt;
  run_contact(state, scene, rom, 10.0, dt);
}
BENCHMARK(RomContactCorrected)->Args({6, 4})->Args({8, 4})->Unit(benchmark::kSecond)->Iterations(1);

// The ROM with N modes stepped implicitly with θ = th/100 at the scene's Δt
// (the front's family (d): the FE's θ = 0.51 damps the modes the step cannot
// resolve), beside RomContact: a Newton solve a step instead of the
// explicit step, and no step limit.
static void RomImplicitContact(benchmark::State &state)
{
  Scene scene                  = default_scene();
  scene.discretisation.n_modes = state.range(0);
  const FEBeam fe(scene);
  RomImplicitBeamSystem rom(
    ReducedOrderModel(make_modal_basis(fe, compute_bending_modes(fe, scene.discretisation.n_modes),
                                       scene.discretisation.n_modes),
                      scene.damping_ratio, scene.discretisation.geometric_nonlinearity),
    scene.beam.thickness_profile(), BaseExcitation::from_scene(scene.excitation), state.range(1) / 100.);
  run_contact(state, scene, rom, 10.0, scene.time_stepping.time_step);
  state.counters["Newton/step"] = double(rom.newton_iterations()) / (10.0 / scene.time_stepping.time_step);
}
BENCHMARK(RomImplicitContact)->Args({5, 51})->Args({10, 51})->Args({15, 51})->Unit(benchmark::kSecond)->Iterations(1);

// Process start-up: `beamslider --help` (no PETSc/SLEPc work), started with
// an argument vector, wall time from fork to exit.
static void StartUp(benchmark::State &state)
{
  double wall = 0;
  for (auto _ : state)
    {
      const auto start = std::chrono::steady_clock::now();
      const pid_t pid  = fork();
      if (pid == 0)
        {
          const int null = open("/dev/null", O_WRONLY);
          dup2(null, 1);
          dup2(null, 2);
          char *argv[] = {const_cast<char *>(BEAMSLIDER_EXECUTABLE), const_cast<char *>("--help"), nullptr};
          execv(argv[0], argv);
          _exit(127);
        }
      int status = 0;
      if (pid < 0 || waitpid(pid, &status, 0) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
        state.SkipWithError("beamslider --help did not run");
      wall += elapsed_seconds(start);
    }
  state.counters["s/start"] = wall / state.iterations();
}
BENCHMARK(StartUp)->Unit(benchmark::kMillisecond)->Iterations(5);

// FE beam with contact (Moreau–Jean, Newton) on 16/32/64 elements with the
// scene's FE model (1e-5 s, θ = 0.51: the error ladder's reference):
// time per step, the Newton counters and the heap allocations per step over
// the window [from, from + 0.2 s] of the signature move. Arg 2 is `from` in seconds: 0 (slider resting at first,
// low amplitude) or 12 (after the jump, on the high branch at ~1.8 h, where
// a 60 s run spends most of its steps). FeContactMidpoint: the midpoint rule
// (θ = ½) at half that step, the reference until 2026-11-27, which sits on
// a plateau of its end state (doc/findings.md): the cost side of the
// choice, per step and per simulated second.
static void fe_contact(benchmark::State &state, const bool midpoint)
{
  Scene scene                         = default_scene();
  if (midpoint)
    {
      scene.time_stepping.fe_time_step /= 2;
      scene.time_stepping.fe_theta = 0.5;
    }
  state.counters["dt [us]"]           = 1e6 * scene.time_stepping.fe_time_step;
  state.counters["theta"]             = scene.time_stepping.fe_theta;
  std::unique_ptr<BeamSystem> system  = make_fe_beam_system(scene, {static_cast<unsigned int>(state.range(0))});
  const auto &fe                      = dynamic_cast<const FETransientBeam &>(*system);
  const double from                   = state.range(1);
  RunOptions options                  = RunOptions::from_scene(scene, scene.time_stepping.fe_time_step);
  options.progress_interval           = 1e300;
  unsigned long steps = 0, allocations = 0, counted_steps = 0;
  double wall = 0, fastest = 0;
  FETransientStatistics before, after;
  for (auto _ : state)
    {
      AdaptationRun run(scene, *system, options);
      run.on_trace_row = [](const TraceRow &row) { benchmark::DoNotOptimize(row.w_center); };
      if (from > 0 && run.run_until(from).status != RunStatus::completed)
        state.SkipWithError("the FE run failed before the window");
      before                 = fe.statistics();
      // The first 0.05 s of the window settle the scratch sizes (trace
      // rows, period records); allocations are counted after them.
      const auto start       = std::chrono::steady_clock::now();
      RunResult result       = run.run_until(from + 0.05);
      const unsigned long settle_steps = result.n_steps;
      heap_counter::start();
      fastest = run_in_chunks(run, from + 0.2, 0.01, options.time_step, result);
      allocations += heap_counter::stop();
      counted_steps += result.n_steps;
      result.n_steps += settle_steps;
      wall += elapsed_seconds(start);
      after = fe.statistics();
      if (result.status != RunStatus::completed)
        state.SkipWithError(result.message.c_str());
      steps += result.n_steps;
      state.counters["x_C/L"] = result.slider_x_over_L;
    }
  const double per_step = 1. / std::max<unsigned long>(after.steps - before.steps, 1);
  state.counters["us/step"]             = 1e6 * wall / std::max<unsigned long>(steps, 1);
  state.counters["us/step fastest"]     = fastest;
  state.counters["simulated s/s"]       = steps * options.time_step / std::max(wall, 1e-300);
  state.counters["newton/step"]         = (after.newton_iterations - before.newton_iterations) * per_step;
  state.counters["factorisations/step"] = (after.factorisations - before.factorisations) * per_step;
  state.counters["contact blocks/step"] = (after.contact_blocks - before.contact_blocks) * per_step;
  state.counters["S^-1 columns/step"]   = (after.inverse_column_solves - before.inverse_column_solves) * per_step;
  state.counters["allocations/step"]    = double(allocations) / std::max<unsigned long>(counted_steps, 1);
}
static void FeContact(benchmark::State &state) { fe_contact(state, false); }
BENCHMARK(FeContact)->Args({16, 0})->Args({32, 0})->Args({64, 0})->Args({32, 12})->Unit(benchmark::kSecond)->Iterations(1);
static void FeContactMidpoint(benchmark::State &state) { fe_contact(state, true); }
BENCHMARK(FeContactMidpoint)->Args({32, 0})->Args({32, 12})->Unit(benchmark::kSecond)->Iterations(1);

// The four coefficient methods for N modes.
static void Coefficients(benchmark::State &state, const std::string &method)
{
  const unsigned int N = state.range(0);
  const FEBeam fe(default_scene());
  const FEModes modes     = compute_bending_modes(fe, N);
  const ModalBasis basis  = make_modal_basis(fe, modes, N);
  for (auto _ : state)
    {
      const CoefficientResult r = compute_coefficients(fe, modes, basis, method, method == "ice" ? 0.03 : 1.0);
      benchmark::DoNotOptimize(r.fit.cubic.data());
      state.counters["static solves"] = r.n_static_solves;
    }
}
BENCHMARK_CAPTURE(Coefficients, step, std::string("step"))->Arg(5)->Arg(7)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Coefficients, step_condensed, std::string("step-condensed"))->Arg(5)->Arg(7)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Coefficients, ice, std::string("ice"))->Arg(5)->Arg(7)->Unit(benchmark::kMillisecond);

// ROM backbone as `beamslider backbone --model rom` computes it: H = 10,
// ŵ/h from 0.01 to 4 with restarts past internal-resonance tongues.
static void RomBackbone(benchmark::State &state)
{
  const unsigned int N = state.range(0);
  const Scene &scene   = default_scene();
  const FEBeam fe(scene);
  const ReducedOrderModel rom(make_modal_basis(fe, compute_bending_modes(fe, N), N), 0.);
  BeamBackboneSettings settings;
  settings.thickness = scene.beam.thickness;
  std::size_t points = 0;
  for (auto _ : state)
    {
      const Backbone b = compute_rom_backbone(rom, 0.5 * scene.beam.length, settings);
      if (!b.completed)
        state.SkipWithError(b.message.c_str());
      points += b.points.size();
    }
  state.counters["points/s"] = benchmark::Counter(points, benchmark::Counter::kIsRate);
}
BENCHMARK(RomBackbone)->Arg(5)->Arg(7)->Unit(benchmark::kMillisecond);

// Harmonic balance on a dense system the size of a condensed FE model: the
// ROM with every bending mode of the default mesh (64) written in
// non-modal coordinates q = P x (P = I + 0.1 S, S a fixed dense matrix with
// entries in [−1, 1]/√n), so that M = PᵀP and K = PᵀΩ²P are full. H = 10,
// ŵ/h from 0.01 to 4; arg 1: odd harmonics only.
static void DenseBackbone(benchmark::State &state)
{
  const Scene &scene = default_scene();
  const FEBeam fe(scene);
  const unsigned int n = fe.n_dofs() - fe.bending_constraints().n_constraints(); // every bending mode
  const FEModes modes  = compute_bending_modes(fe, n);
  const ModalBasis basis = make_modal_basis(fe, modes, n);
  const ReducedOrderModel rom(basis, 0.);
  Eigen::MatrixXd S(n, n);
  for (unsigned int i = 0; i < n; ++i)
    for (unsigned int j = 0; j < n; ++j)
      S(i, j) = std::sin(1.7 * i + 0.3 * j * j + 0.1) / std::sqrt(double(n));
  const Eigen::MatrixXd P = Eigen::MatrixXd::Identity(n, n) + 0.1 * S;
  ConservativeSystem dense;
  dense.mass      = P.transpose() * P;
  dense.stiffness = P.transpose() * basis.omega.array().square().matrix().asDiagonal() * P;
  dense.force     = [&](const Eigen::VectorXd &x) -> Eigen::VectorXd { return P.transpose() * rom.nonlinear_force(P * x); };
  dense.tangent   = [&](const Eigen::VectorXd &x) -> Eigen::MatrixXd {
    return P.transpose() * rom.nonlinear_tangent(P * x) * P;
  };
  Eigen::VectorXd phi, dphi;
  basis.evaluate(0.5 * scene.beam.length, phi, dphi);
  BackboneSettings settings;
  settings.output                = P.transpose() * phi;
  settings.hb.n_harmonics        = 10;
  settings.hb.odd_harmonics_only = state.range(0) == 1;
  settings.start_amplitude       = 0.01 * scene.beam.thickness;
  settings.end_amplitude         = 4 * scene.beam.thickness;
  unsigned long iterations = 0, points = 0, unknowns = 0;
  double seconds = 0;
  for (auto _ : state)
    {
      const Backbone bb = compute_backbone(dense, settings);
      for (const auto &p : bb.points)
        if (!(p.relative_residual < 1e-8))
          state.SkipWithError("a backbone point is not converged");
      iterations += bb.n_newton_iterations;
      points += bb.points.size();
      seconds += bb.seconds;
      unknowns = bb.points.empty() ? 0 : bb.points.front().harmonics.size() + 1;
    }
  state.counters["unknowns"]     = unknowns;
  state.counters["points"]       = double(points) / state.iterations();
  state.counters["ms/iteration"] = 1e3 * seconds / std::max<unsigned long>(iterations, 1);
}
BENCHMARK(DenseBackbone)->Arg(1)->Arg(0)->Unit(benchmark::kSecond)->Iterations(1);

// The FE backbone at small amplitude (H = 3, ŵ/h ≤ 0.3): the FE-implied b_111.
static void FeImpliedCoefficient(benchmark::State &state)
{
  const FEBeam fe(default_scene());
  const FEModes modes = compute_bending_modes(fe, 1);
  for (auto _ : state)
    benchmark::DoNotOptimize(fe_implied_b111(fe, modes).b_111);
}
BENCHMARK(FeImpliedCoefficient)->Unit(benchmark::kMillisecond);

// The 3D strip of report section 8 (mueller2023, 70 × 4 × 1 Q2 elements,
// ν = 0.3): one assembly of the solid's internal force (arg 0) or of the
// force and its tangent (arg 1), the inner loop of its statics and ICE.
static void SolidAssembly(benchmark::State &state)
{
  const Scene scene = read_scene(BEAMSLIDER_SOURCE_DIR "/meshes/mueller2023.prm", solid_strip_3d_overrides());
  const SolidModel<3> model(scene, MPI_COMM_SELF);
  dealii::PETScWrappers::MPI::Vector u, f;
  dealii::PETScWrappers::MPI::SparseMatrix K;
  model.reinit_ghosted_vector(u);
  for (auto _ : state)
    model.assemble_internal_force(u, &f, state.range(0) ? &K : nullptr);
  state.counters["DoFs"] = model.n_dofs();
}
BENCHMARK(SolidAssembly)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

int main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv))
    return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
