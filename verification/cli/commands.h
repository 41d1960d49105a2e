// The sub-commands of the `beamslider` executable. Each reads a scene, writes
// CSV (named columns, SI units) and plots into an output folder, and returns
// the process exit code. User errors are thrown as InputError.
#pragma once

#include "verification/report/charts.h"

#include <any>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace beamslider
{
  // The exit code of a command that finished and wrote its results, but
  // whose reference did not prove its convergence (convergence_check.h): the
  // results are marked so; a script can tell it from success (0) and from
  // failure (1).
  constexpr int not_converged_exit_code = 3;

  // A study computed in one call and written in another: the Python
  // module's study objects (python/study_bindings.cc) hold the result in
  // memory and write its folder only when asked. With `compute`, a command
  // that supports it (ensemble, ladder, sweep, map) checks its input and computes as
  // always, keeps the result in `result` and writes nothing; with `write`, it
  // checks the same input again and writes the kept result into its folder,
  // exactly as it writes a result it has just computed (the same files and
  // run record), without computing it again. Other commands refuse it.
  struct StudyHandover
  {
    enum class Mode
    {
      compute,
      write
    };
    Mode mode = Mode::compute;
    std::any result; // the command's own result type (EnsembleRun, LadderRun, SweepRun, MapCells: study_results.h)
    // Refused (InputError) by a command that cannot hand its study over.
    static void refuse(const StudyHandover *handover, const std::string &command);
  };
  struct Scene;
  // Refuses (InputError) to write a kept study whose scene is not the one
  // the command reads now (its scene file changed in between).
  void require_same_scene(const Scene &kept, const Scene &now, const std::string &command);

  struct CommonOptions
  {
    std::string scene_file;             // path to a .prm scene
    std::vector<std::string> overrides; // "Section/Name=value"
    std::string output_dir;             // "" = reports/<scene name>/<command>
  };

  struct ModesOptions
  {
    unsigned int n_modes = 7;
    std::optional<double> slider_at; // x_C/L of a bonded slider
    unsigned int n_elements = 0;     // 0 = the scene's mesh
  };
  int run_modes(const CommonOptions &common, const ModesOptions &options);
  // The modes of a scene's solid (command_modes_solid.cc); n_bending bending modes.
  struct Scene;
  int run_solid_modes(const CommonOptions &common, const Scene &scene, unsigned int n_bending);

  struct VerifyOptions
  {
    bool full = false; // the long studies (minutes to hours)
    bool diagnostics = false; // with full: the error ladder's diagnostic rungs too
    std::vector<unsigned int> sections; // only these sections (1–8); empty = all
    // Internal: this verify is a part of another one writing into the same
    // folder (section 8 run beside sections 1–7): no run record, no header,
    // the sections' text into this file instead of report.md.
    std::string part_file;
  };
  int run_verify(const CommonOptions &common, const VerifyOptions &options);

  struct CoefficientsOptions
  {
    std::string method = "analytic"; // analytic | step | step-condensed | ice; a solid: exact | step | ice
    unsigned int n_modes = 0;        // 0 = the scene's N
    // A solid: the modes by their index in modes.csv (1-based, every shape,
    // ascending frequency) instead of the first n_modes bending modes.
    std::vector<unsigned int> mode_indices;
  };
  int run_coefficients(const CommonOptions &common, const CoefficientsOptions &options);
  // A solid scene's coefficients (command_coefficients_solid.cc): exact | step
  // | ice, of its first n_modes bending modes or of the modes `mode_indices`
  // (1-based, when not empty).
  int run_solid_coefficients(const CommonOptions &common, const Scene &scene, const std::string &method,
                             unsigned int n_modes, const std::vector<unsigned int> &mode_indices = {});

  // `beamslider statics`: load-stepped nonlinear statics of the FE beam under
  // a uniform dead line load (command_statics.cc).
  struct StaticsOptions
  {
    // Exactly one of the two loads:
    std::optional<double> line_load_n_per_m; // Q [N/m], uniform, positive downward
    std::optional<double> modal_load;        // f̂ [N kg^-1/2]: the load M φ_n f̂ on bending mode n
    unsigned int mode    = 1;  // n (1-based) of the modal load
    unsigned int n_steps = 10; // equal load steps to the full load
  };
  // statics.csv's columns, for both the beam and the solid: q_m_sqrt_kg is
  // the loaded mode's coordinate φ_nᵀ M u under a modal load.
  inline std::vector<std::string> statics_csv_columns(const StaticsOptions &options)
  {
    if (options.modal_load)
      return {"modal_load_n_per_sqrt_kg", "q_m_sqrt_kg", "w_mid_m", "newton_iterations"};
    return {"line_load_n_per_m", "w_mid_m", "newton_iterations"};
  }
  int run_statics(const CommonOptions &common, const StaticsOptions &options);
  // A solid scene's statics (command_statics_solid.cc).
  int run_solid_statics(const CommonOptions &common, const Scene &scene, const StaticsOptions &options);

  struct BackboneOptions
  {
    std::string model = "rom"; // rom | fe
    unsigned int n_modes = 0;  // ROM: 0 = the scene's N
    unsigned int n_harmonics = 10;
    double max_amplitude_over_h = 4.;
  };
  int run_backbone(const CommonOptions &common, const BackboneOptions &options);

  struct SimulateOptions
  {
    std::string model = "rom";        // rom | fe | auto
    std::string case_name;            // a published case or ablation ("" = the scene as it is)
    std::optional<double> end_time;   // [s], overrides the scene's/case's
    bool animate = false;             // also write a .pvd animation
    std::optional<double> tolerance;  // for --model auto
    bool allow_large_output = false;  // more than max_trace_rows rows in trace.csv
    std::optional<double> checkpoint_every; // [s] simulated between checkpoints (checkpoint.bin)
    std::string resume_dir;           // continue the run whose checkpoint is in this folder

    // trace.csv rows (End time × Output rate) allowed without
    // --allow-large-output: 1e7 rows are about 1 GB.
    static constexpr double max_trace_rows = 1e7;
  };
  int run_simulate(const CommonOptions &common, const SimulateOptions &options);
  // simulate's run, returning what happened (SimulationOutcome: studies/simulation_cases.h).
  struct SimulationOutcome;
  SimulationOutcome run_simulation(const CommonOptions &common, const SimulateOptions &options, bool verbose = true);

  struct SweepOptions
  {
    std::string model = "rom";           // rom | fe
    double step_over_L = 0.003;          // Δx_C/L
    std::optional<double> low_over_L;    // range; default: the half of the beam
    std::optional<double> high_over_L;   //   holding the scene's initial position
    double settle_time  = 0.5;           // [s] per position before averaging
    double average_time = 0.2;           // [s] averaged per position
    std::optional<double> free_time;     // [s] free-slider run overlaid; default the scene's end time
    std::string case_name;               // a published case or ablation ("" = the scene as it is)
    std::string against;                 // another sweep's folder (same positions) to compare with
  };
  int run_sweep(const CommonOptions &common, const SweepOptions &options, StudyHandover *handover = nullptr);

  struct BranchesOptions
  {
    std::optional<double> low_over_L, high_over_L; // range; default: the sweep's
    double probe_step_over_L = 0.02;               // between attractor probes
    unsigned int settle_periods = 120;             // per probe
    std::string case_name;                         // a published case or ablation
  };
  int run_branches(const CommonOptions &common, const BranchesOptions &options);

  struct AnimateOptions
  {
    std::string model = "fe";
    std::optional<double> end_time;   // [s]
    double start_time = 0;            // [s] first frame written
    double frame_rate = 2000;         // frames per simulated second
    double magnification = 1;         // deformation scale written into the files
    std::string case_name;
  };
  int run_animate(const CommonOptions &common, const AnimateOptions &options);

  struct EnsembleOptions
  {
    std::string model = "rom";      // rom | fe | auto (model_choice.h)
    std::optional<double> tolerance; // --model auto
    std::string case_name;          // a published case or ablation
    unsigned int members = 8;       // K
    double perturbation  = 1e-9;    // shift of the start x_C/L per member index [-]
    std::optional<double> end_time; // [s]
    std::string against;            // another ensemble's folder to compare with
    std::string integrator = "explicit"; // rom: explicit | implicit (the FE's scheme)
    std::optional<double> theta;         // rom implicit: θ of the Moreau–Jean scheme (default 0.5)
    // rom: the cubic coefficients (ModelSetting::coefficients); empty: the
    // scene's default (analytic on a beam, ICE from the solid on a solid)
    std::string coefficients;
    // fe: skip the convergence check in Δt (convergence_check.h); the
    // result then says that it is unchecked.
    bool unchecked = false;
  };
  int run_ensemble_command(const CommonOptions &common, const EnsembleOptions &options,
                           StudyHandover *handover = nullptr);

  // `beamslider ladder`: the error ladder alone (report section 5.1–5.2),
  // with a choice of rungs, members and end time (command_ladder.cc).
  struct LadderOptions
  {
    bool full = false;              // the rungs of `verify --full` (default: those of the quick report)
    bool diagnostics = false;       // and the diagnostic rungs (implies full)
    std::vector<std::string> rungs; // names of rungs of LadderScope::every; the reference always runs
    std::optional<unsigned int> members; // default 4 (quick) or 8 (full)
    std::optional<double> end_time;      // [s], default 25 (quick) or 40 (full)
  };
  int run_ladder_command(const CommonOptions &common, const LadderOptions &options, StudyHandover *handover = nullptr);

  // `beamslider map`: the adaptation over a grid of scene parameters, on MPI
  // ranks when started by mpirun (command_map.cc).
  struct MapOptions
  {
    std::string frequency;          // "A:B:STEP" [Hz] or one value; "" = not an axis
    std::string acceleration;       // [m/s²]
    std::string start;              // x_C/L [-]
    std::vector<std::string> axes;  // "Section/Name=A:B:STEP"
    std::string model = "rom";      // rom | fe | auto (model_choice.h, on the scene without the axes)
    std::optional<double> tolerance; // --model auto
    unsigned int members = 1;       // K per cell
    double perturbation  = 1e-9;    // shift of the start x_C/L per member index [-]
    std::optional<double> end_time; // [s]; default the scene's
  };
  int run_map(const CommonOptions &common, const MapOptions &options, StudyHandover *handover = nullptr);

  // `beamslider identify`: System 1's unknowns by the seed's facts, one map
  // per fact over the unknowns (command_identify.cc, studies/system1_facts.h).
  struct IdentifyOptions
  {
    std::vector<std::string> axes;  // the unknowns, "Section/Name=A:B:STEP"
    std::vector<std::string> facts; // fact ids; empty = every fact
    unsigned int members = 1;       // K per run
    double perturbation  = 1e-9;    // shift of the start x_C/L per member index [-]
  };
  int run_identify(const CommonOptions &common, const IdentifyOptions &options);

  // The scene of a command that simulates: the scene file, or with a case
  // name the file with the case's parameters (simulation_cases.h); the
  // user's overrides last. `modified` lists the case's own parameters the
  // user changed.
  struct CommandSetting;
  Scene read_command_scene(const CommonOptions &common, const std::string &case_name,
                           std::vector<std::string> *modified = nullptr);

  // Resolves a scene argument: the path as given, else relative to the
  // source tree's meshes/ (so `beamslider modes mueller2023` works anywhere).
  std::string resolve_scene_path(const std::string &scene);
  // Refuses (InputError) a mesh too coarse for n_modes bending modes: at
  // least n_modes + 1 elements (the rule validate_scene applies to the
  // scene's own N), so that the eigensolver has the DoFs to find them.
  void require_mesh_for_modes(unsigned int n_elements, unsigned int n_modes, const std::string &option);

  // Creates (if needed) and returns the output folder for a command, and
  // writes into it what repeats the run from the folder alone:
  //   parameters.prm  the scene as this run uses it (after --set and --case),
  //                   complete, in the scene-file format (read_scene reads it
  //                   back bit for bit);
  //   command.prm     every option of the command with its effective value,
  //                   given or default (recorded by main(), see
  //                   record_command_settings), e.g. harmonics, sweep times;
  //   run.txt         the command line, working directory, time (UTC),
  //                   beamslider version and source revision; a run that
  //                   continues the folder's run (simulate --resume) appends
  //                   its record, so the folder keeps every one (and
  //                   parameters.prm and command.prm stay those of the run
  //                   it continues).
  // Before that it takes the folder for this run (lock_output_folder: exit 1
  // if a live process holds it) and, for a new run, removes the result files
  // the command writes (command_common.cc, result_files), so that no file in
  // the folder is left from another run.
  // Throws OutputError if the folder or either file cannot be written.
  enum class RunRecord
  {
    replace,
    append
  };
  std::string prepare_output_dir(const CommonOptions &common, const Scene &scene, const std::string &command,
                                 RunRecord record = RunRecord::replace);
  // The folder prepare_output_dir would prepare, untouched (for a command
  // that must check what the folder holds before it writes there).
  std::string output_dir_path(const CommonOptions &common, const Scene &scene, const std::string &command);

  // Appends to run.txt in every folder the command wrote into how it ended:
  // completed, or failed / refused / interrupted with its exit status, the
  // first line of `messages` and that the folder's results are partial.
  // Returns false (and says why on `errors`) if a record could not be written.
  bool record_run_end(int status, const std::string &messages, std::ostream &errors);

  // The process's command line, for run.txt (main() records it first).
  void record_command_line(int argc, const char *const *argv);
  // The sub-command's options with their effective values, for command.prm
  // (main() records them once the command line is parsed).
  void record_command_settings(const std::string &command, const std::vector<CommandSetting> &settings);
} // namespace beamslider
