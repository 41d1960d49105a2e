// `beamslider simulate SCENE --model rom|fe|auto [--case NAME]`: the free
// slider on the ROM (N modes of the FE basis, analytic coefficients; on a
// scene with a Solid, N modes of the solid with its ICE coefficients) or on
// the FE beam, through the shared contact code (runs/adaptation_run.h).
//
// Writes into the output folder:
//   trace.csv    t_s,slider_x_over_L,slider_z_m,slider_beta_rad,w_center_m,
//                w_probe_m,amplitude_over_h at the scene's output rate (w
//                relative to the base; probe at 4L/7; amplitude = (max − min)/2
//                of w(L/2) over the last excitation period, / h)
//   periods.csv  one row per excitation period, with the energy bookkeeping
//   trace.png    beam deflection at L/2 and slider position against time
//                (like seed Figs. 5–8)
//   summary.md   settings, cost, status and a one-line verdict
//   animation.pvd (+ files) with --animate: the last 0.1 s at 2000 frames/s
// Both CSV files are flushed as the run goes: a stopped run keeps them.
#include "runs/adaptation_run.h"
#include "io/checkpoint.h"
#include "io/csv_writer.h"
#include "io/interruption.h"
#include "io/input_file.h"
#include "io/output_file.h"
#include "fem/output/vtk_animation.h"
#include "meshes/scene.h"
#include "verification/cli/commands.h"
#include "verification/cli/ladder_cache.h"
#include "numerics/elapsed.h"
#include "io/console.h"
#include "verification/studies/fe_rom_study.h"
#include "verification/studies/simulation.h"
#include "verification/studies/simulation_cases.h"

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <sys/stat.h>
#include <unistd.h>
#include <optional>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

namespace beamslider
{
  namespace
  {
    // The animation window of --animate: the end of the run, where the
    // adaptation has happened, at a frame rate that resolves the excitation.
    constexpr double animation_window = 0.1;   // [s]
    constexpr double animation_rate   = 2000.; // frames per simulated second

    // What a checkpoint must say besides the run's state: how the run was
    // asked for (so that --resume rebuilds the same model), where its files
    // end, and the period records the verdict needs.
    struct RunDescription
    {
      std::string scene_file; // absolute
      std::uint64_t scene_hash = 0;
      std::vector<std::string> overrides;
      std::string case_name;
      ModelSetting setting;
      double end_time = 0;
      std::string why;
      // What defines the run (format 3): the command, the model and the
      // scene as parameters.prm holds it, and its digest.
      std::string identity, scene_text;
      std::uint64_t identity_digest = 0;
      std::uint64_t trace_bytes = 0, period_bytes = 0; // file sizes at the checkpoint
      // FNV-1a of those bytes (format 3): a resume checks that the files it
      // continues are the ones the checkpoint's run wrote.
      std::uint64_t trace_digest = 0, period_digest = 0;
      std::uint64_t n_steps     = 0;
      double wall_seconds       = 0;
      std::vector<PeriodRecord> periods;
    };

    // The scene's content: the file's bytes, the overrides and the case, so
    // that a checkpoint is refused when any of them changed.
    std::uint64_t scene_content_hash(const std::string &scene_file, const std::vector<std::string> &overrides,
                                     const std::string &case_name)
    {
      std::uint64_t hash = fnv1a(read_text_file(scene_file, InputLimits::scene));
      for (const auto &o : overrides)
        hash = fnv1a(o + '\n', hash);
      return fnv1a("case:" + case_name, hash);
    }

    // The run's identity: what a resumed run must share with the run it
    // continues. The end time is not part of it (--resume --end-time T
    // extends a run), the scene's other parameters, the command and the model
    // are.
    std::string run_identity(const std::string &command, const ModelSetting &setting, const std::string &scene_text)
    {
      return "command: " + command + "\nmodel: " + setting.label() + ", coefficients " + setting.coefficients +
             ", integrator " + setting.integrator + ", axial inertia " + (setting.axial_inertia ? "1" : "0") +
             ", damped modes " + std::to_string(setting.damped_modes) + ", theta " + CsvWriter::cell(setting.theta, 17) +
             ", time step " + CsvWriter::cell(setting.time_step, 17) + "\n" + scene_text;
    }

    // The parameters of a scene text (parameters.prm's format) as
    // "Section/Name" and the rest of its line, in order; not the end time.
    std::vector<std::pair<std::string, std::string>> scene_settings(const std::string &text)
    {
      std::vector<std::pair<std::string, std::string>> settings;
      std::vector<std::string> sections;
      std::istringstream in(text);
      for (std::string line; std::getline(in, line);)
        {
          const std::size_t first = line.find_first_not_of(" \t");
          if (first == std::string::npos)
            continue;
          line = line.substr(first);
          if (line.rfind("subsection ", 0) == 0)
            sections.push_back(line.substr(11));
          else if (line == "end" && !sections.empty())
            sections.pop_back();
          else if (line.rfind("set ", 0) == 0)
            {
              const std::size_t equals = line.find(" = ");
              std::string name;
              for (const std::string &s : sections)
                name += s + "/";
              name += line.substr(4, equals == std::string::npos ? std::string::npos : equals - 4);
              name.erase(name.find_last_not_of(' ') + 1); // the names are padded to align the values
              if (name != "Time stepping/End time")
                settings.emplace_back(name, equals == std::string::npos ? std::string() : line.substr(equals + 3));
            }
        }
      return settings;
    }

    // The first parameter in which two scene texts differ ("" if none).
    std::string first_difference(const std::string &folder_text, const std::string &checkpoint_text)
    {
      const auto a = scene_settings(folder_text), b = scene_settings(checkpoint_text);
      for (std::size_t i = 0; i < std::max(a.size(), b.size()); ++i)
        {
          if (i < a.size() && i < b.size() && a[i] == b[i])
            continue;
          if (i < a.size() && i < b.size() && a[i].first == b[i].first)
            return "'" + a[i].first + "' is " + a[i].second + " in parameters.prm, " + b[i].second +
                   " in the checkpoint's run";
          return "'" + (i < a.size() ? a[i].first : b[i].first) + "' is in " +
                 (i < a.size() ? "parameters.prm" : "the checkpoint's run") + " only";
        }
      return std::string();
    }

    // The length and FNV-1a digest of a file's first bytes, extended to its
    // end as the run writes it: at each checkpoint only the new bytes are
    // read.
    struct FileDigest
    {
      std::uint64_t bytes = 0;
      std::uint64_t hash  = fnv1a("");
    };

    void extend_digest(const std::string &path, FileDigest &digest, const std::uint64_t up_to)
    {
      const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
      if (fd < 0)
        throw FileReadError("file '" + path + "' cannot be opened for reading: " + std::strerror(errno));
      std::string buffer(1 << 16, '\0');
      while (digest.bytes < up_to)
        {
          const std::size_t want = static_cast<std::size_t>(std::min<std::uint64_t>(buffer.size(), up_to - digest.bytes));
          const ssize_t n        = ::pread(fd, buffer.data(), want, static_cast<off_t>(digest.bytes));
          if (n < 0 && errno == EINTR)
            continue;
          if (n <= 0)
            break; // shorter than up_to: the caller compares the length
          digest.hash = fnv1a(buffer.substr(0, static_cast<std::size_t>(n)), digest.hash);
          digest.bytes += static_cast<std::uint64_t>(n);
        }
      ::close(fd);
    }

    // Before a resume appends to `file`: it must be the file the checkpoint's
    // run wrote, at least as long as then, with the same first bytes.
    // Never padded: a file cut short or changed is refused.
    void check_continued_file(const std::string &dir, const std::string &name, const std::uint64_t bytes,
                              const std::uint64_t hash)
    {
      const std::string file = dir + "/" + name;
      struct stat status;
      const bool present = ::lstat(file.c_str(), &status) == 0;
      if (!present || !S_ISREG(status.st_mode))
        throw InputError("--resume: '" + file + "' is " +
                         (!present ? std::string("missing") : std::string("not a regular file (a link?)")) +
                         "; the checkpoint in '" + dir + "' continues it, so the run cannot be resumed");
      if (static_cast<std::uint64_t>(status.st_size) < bytes)
        throw InputError("--resume: '" + file + "' holds " + std::to_string(status.st_size) + " bytes, fewer than the " +
                         std::to_string(bytes) + " it had at the checkpoint (cut short since); not resumed");
      FileDigest digest;
      extend_digest(file, digest, bytes);
      if (digest.bytes != bytes || digest.hash != hash)
        throw InputError("--resume: the first " + std::to_string(bytes) + " bytes of '" + file +
                         "' are not those the checkpoint's run wrote (changed since, or another run's); not resumed");
    }

    void save_description(CheckpointWriter &out, const RunDescription &d)
    {
      out.put(d.scene_file);
      out.put(d.scene_hash);
      out.put(std::uint64_t(d.overrides.size()));
      for (const auto &o : d.overrides)
        out.put(o);
      out.put(d.case_name);
      save_setting(out, d.setting);
      out.put(d.end_time);
      out.put(d.why);
      out.put(d.identity);
      out.put(d.scene_text);
      out.put(d.identity_digest);
      out.put(d.trace_bytes);
      out.put(d.trace_digest);
      out.put(d.period_bytes);
      out.put(d.period_digest);
      out.put(d.n_steps);
      out.put(d.wall_seconds);
      out.put(std::uint64_t(d.periods.size()));
      for (const auto &p : d.periods)
        save_period(out, p);
    }

    RunDescription load_description(CheckpointReader &in)
    {
      RunDescription d;
      d.scene_file = in.get_string();
      d.scene_hash = in.get_uint();
      d.overrides.resize(in.get_count(sizeof(std::uint64_t))); // each a length and its text
      for (auto &o : d.overrides)
        o = in.get_string();
      d.case_name           = in.get_string();
      d.setting             = load_setting(in);
      d.end_time            = in.get_double();
      d.why                 = in.get_string();
      d.identity            = in.get_string();
      d.scene_text          = in.get_string();
      d.identity_digest     = in.get_uint();
      d.trace_bytes         = in.get_uint();
      d.trace_digest        = in.get_uint();
      d.period_bytes        = in.get_uint();
      d.period_digest       = in.get_uint();
      d.n_steps             = in.get_uint();
      d.wall_seconds        = in.get_double();
      const std::uint64_t n = in.get_count(17 * sizeof(std::uint64_t)); // a period record's 17 numbers
      for (std::uint64_t i = 0; i < n; ++i)
        d.periods.push_back(load_period(in));
      return d;
    }

    // The state of one `simulate` run, shared by its stages: the options
    // (with --resume, those of the checkpoint's run), the checkpoint it
    // continues, the scene, what defines the run, and what it has written.
    struct SimulationRun
    {
      CommonOptions common;
      SimulateOptions options;
      bool resuming = false;
      std::optional<CheckpointReader> checkpoint; // --resume: read up to the run's state
      RunDescription saved;                       // --resume: the checkpoint's run
      std::string scene_file;                     // absolute
      const SimulationCase *the_case = nullptr;
      std::vector<std::string> modified; // the case's own parameters the user changed
      // What defines this run, as its checkpoints record it: the scene as
      // parameters.prm holds it, and (for the digest) without its end time.
      std::string command_label, scene_text, timeless_scene_text;
      FileDigest trace_digest, period_digest; // of the files' bytes up to the last checkpoint
      std::chrono::steady_clock::time_point start; // of the time stepping
      SimulationOutcome outcome; // the scene, model, folder, result and period records
    };

    // --resume DIR: the scene, overrides, case and model come from DIR's
    // checkpoint, which is read up to the run's state.
    void load_checkpoint_to_resume(SimulationRun &r)
    {
      SimulateOptions &options = r.options;
      if (options.animate)
        throw InputError("--resume cannot be combined with --animate; animate the end of the resumed run with "
                         "`beamslider animate`");
      // Held before anything in it is read: a live run there would change
      // the files being checked (exit 1, "in use").
      if (std::filesystem::is_directory(options.resume_dir))
        lock_output_folder(options.resume_dir);
      const std::string checkpoint_file = options.resume_dir + "/checkpoint.bin";
      try
        {
          r.checkpoint.emplace(read_checkpoint_file(checkpoint_file));
        }
      catch (const CheckpointError &e)
        {
          throw InputError(std::string("--resume: ") + e.what());
        }
      try
        {
          r.saved = load_description(*r.checkpoint);
        }
      catch (const CheckpointError &e)
        {
          throw InputError("--resume: '" + checkpoint_file + "': " + e.what());
        }
      r.common.scene_file = r.saved.scene_file;
      r.common.overrides  = r.saved.overrides;
      r.common.output_dir = options.resume_dir;
      options.case_name   = r.saved.case_name;
      options.model       = r.saved.setting.family;
      if (!options.end_time)
        options.end_time = r.saved.end_time;
    }

    // The checkpoint must be of the scene it names, as it is now, and of the
    // run the folder holds (a checkpoint left by an earlier run, or copied
    // in, is not), and the files it continues must be as that run left them.
    // Checked before anything in the folder is touched.
    void check_checkpoint_is_folders_run(const SimulationRun &r)
    {
      const RunDescription &saved    = r.saved;
      const std::string &resume_dir = r.options.resume_dir;
      std::uint64_t scene_hash       = 0;
      try
        {
          scene_hash = scene_content_hash(saved.scene_file, saved.overrides, saved.case_name);
        }
      catch (const FileReadError &e)
        {
          throw InputError("--resume: the checkpoint in '" + resume_dir + "' was written for the scene '" +
                           saved.scene_file + "', which cannot be read now: " + e.what());
        }
      if (scene_hash != saved.scene_hash)
        throw InputError("--resume: the checkpoint in '" + resume_dir + "' was written for another scene: '" +
                         saved.scene_file + "' or its parameters changed since; a resumed run would not continue "
                         "the same computation");
      std::string folder_scene;
      try
        {
          folder_scene = read_text_file(resume_dir + "/parameters.prm", InputLimits::text);
        }
      catch (const FileReadError &e)
        {
          throw InputError("--resume: the folder's scene cannot be read, so the run it holds is not known: " +
                           std::string(e.what()));
        }
      const std::string difference = first_difference(folder_scene, saved.scene_text);
      if (!difference.empty())
        throw InputError("--resume: the checkpoint in '" + resume_dir + "' is of another run than the folder's: " +
                         difference + "; not resumed");
      check_continued_file(resume_dir, "trace.csv", saved.trace_bytes, saved.trace_digest);
      check_continued_file(resume_dir, "periods.csv", saved.period_bytes, saved.period_digest);
    }

    void check_simulate_options(const SimulateOptions &options)
    {
      if (options.checkpoint_every && options.animate)
        throw InputError("--checkpoint-every cannot be combined with --animate");

      if (options.model != "rom" && options.model != "fe" && options.model != "auto")
        throw InputError("--model '" + options.model + "' is not one of rom, fe, auto");
      if (options.end_time && !(*options.end_time > 0.))
        throw InputError("--end-time " + std::to_string(*options.end_time) + " s must be > 0");
    }

    // The scene (and case) as the run uses it, with --end-time; refused if
    // its trace would be too large.
    void read_simulation_scene(SimulationRun &r)
    {
      const SimulateOptions &options = r.options;
      r.scene_file = std::filesystem::absolute(resolve_scene_path(r.common.scene_file)).string();
      r.the_case   = options.case_name.empty() ? nullptr : &find_case(options.case_name);
      Scene &scene = r.outcome.scene;
      scene        = read_command_scene(r.common, options.case_name, &r.modified);
      if (options.end_time)
        {
          scene.time_stepping.end_time = *options.end_time;
          validate_scene(scene); // the step count limit
        }
      const double n_rows = scene.time_stepping.end_time * scene.time_stepping.output_rate;
      if (n_rows > SimulateOptions::max_trace_rows && !options.allow_large_output)
        {
          std::ostringstream m;
          m << "End time " << scene.time_stepping.end_time << " s at Output rate " << scene.time_stepping.output_rate
            << " 1/s would write " << n_rows << " rows to trace.csv, more than " << SimulateOptions::max_trace_rows
            << " (about 1 GB); lower 'Time stepping/Output rate' or pass --allow-large-output";
          throw InputError(m.str());
        }
    }

    // The run goes in pieces of --checkpoint-every, each ending in a
    // checkpoint: pieces shorter than a time step hold no step, and the run
    // writes checkpoints without getting on (it never ended). The bound is
    // the step of the model the run uses; --model auto has not chosen yet,
    // so it takes the larger of the ROM's and the FE's.
    void check_checkpoint_interval(const SimulationRun &r)
    {
      const SimulateOptions &options = r.options;
      const Scene &scene             = r.outcome.scene;
      const double rom_step = scene_model(scene, "rom").time_step, fe_step = scene_model(scene, "fe").time_step;
      const double step = r.resuming                 ? r.saved.setting.time_step
                          : options.model == "rom"   ? rom_step
                          : options.model == "fe"    ? fe_step
                                                     : std::max(rom_step, fe_step);
      const std::string which =
        r.resuming ? "the resumed run's time step"
        : options.model == "rom" ? "the ROM's 'Time stepping/Time step'"
        : options.model == "fe"  ? "the FE's 'Time stepping/FE time step'"
                                 : "the larger of the ROM's and the FE's time steps (--model auto may run either)";
      if (!(*options.checkpoint_every >= step))
        {
          std::ostringstream m;
          m << "--checkpoint-every " << *options.checkpoint_every << " s is outside the allowed range [" << step
            << ", inf): at least " << which << ", " << step << " s";
          throw InputError(m.str());
        }
    }

    // What defines this run (its command, scene and scene without end time)
    // and, on --resume, that it is the checkpoint's run.
    void describe_run(SimulationRun &r)
    {
      const Scene &scene = r.outcome.scene;
      r.command_label    = r.the_case ? "simulate/" + r.the_case->name : std::string("simulate");
      r.scene_text       = scene_file_text(scene);
      {
        Scene timeless                  = scene;
        timeless.time_stepping.end_time = 0.;
        r.timeless_scene_text           = scene_file_text(timeless);
      }
      if (!r.resuming)
        return;
      const std::string identity = run_identity(r.command_label, r.saved.setting, r.timeless_scene_text);
      if (fnv1a(identity) != r.saved.identity_digest)
        {
          // The scene file reads differently now (another build's defaults):
          // the first line in which the two runs differ.
          const auto lines = first_differing_lines(identity, r.saved.identity);
          throw InputError("--resume: the checkpoint in '" + r.options.resume_dir +
                           "' is of another run: this run has '" + (lines ? lines->first : identity) +
                           "' where the checkpoint's has '" + (lines ? lines->second : r.saved.identity) +
                           "'; not resumed");
        }
    }

    // The model: as asked, or the cheapest whose ensemble end state the
    // scene's error ladder puts within the tolerance of the FE reference's.
    void choose_model(SimulationRun &r)
    {
      const Scene &scene    = r.outcome.scene;
      ModelSetting &setting = r.outcome.setting;
      setting = scene_model(scene, r.options.model == "fe" ? "fe" : "rom"); // the FE at the scene's FE time step
      if (r.resuming)
        {
          setting      = r.saved.setting;
          r.outcome.why = r.saved.why;
        }
      else if (r.options.model == "auto")
        {
          // The ladder is cached beside the scene's reports, keyed by its content.
          setting = choose_model(scene, r.options.tolerance, choice_cache_dir(scene), r.outcome.why);
          console() << r.outcome.why << std::endl;
        }
    }

    // --resume: the run's state from the checkpoint, and its files cut back
    // to it. Rows written after the checkpoint by the run that stopped are
    // dropped; the resumed run writes them again, identically. (Only ever
    // shorter: the files were checked to be at least this long.)
    void restore_checkpointed_run(SimulationRun &r, AdaptationRun &run)
    {
      const std::string &dir = r.outcome.dir;
      try
        {
          run.load(*r.checkpoint);
          if (!r.checkpoint->at_end())
            throw CheckpointError("the checkpoint holds more than this model's state");
        }
      catch (const CheckpointError &e)
        {
          throw InputError("--resume: checkpoint in '" + dir + "' does not fit the model: " + e.what());
        }
      const double end_time = r.outcome.scene.time_stepping.end_time;
      if (!(end_time > run.state().t))
        {
          std::ostringstream m;
          m << "--resume: --end-time " << end_time << " s must lie after the checkpoint's time " << run.state().t
            << " s";
          throw InputError(m.str());
        }
      for (const auto &[file, size] : {std::pair(dir + "/trace.csv", r.saved.trace_bytes),
                                       std::pair(dir + "/periods.csv", r.saved.period_bytes)})
        {
          std::error_code ec;
          std::filesystem::resize_file(file, size, ec);
          if (ec)
            throw OutputError("--resume: '" + file + "' cannot be cut back to the checkpoint: " + ec.message());
        }
      r.outcome.periods = r.saved.periods;
      r.trace_digest    = {r.saved.trace_bytes, r.saved.trace_digest};
      r.period_digest   = {r.saved.period_bytes, r.saved.period_digest};
      console() << "resuming from t = " << run.state().t << " s (checkpoint in " << dir << ")" << std::endl;
    }

    // trace.csv and periods.csv, streams that a stopped run keeps; a resumed
    // run appends to the files it continues. The trace (1000 rows per
    // simulated second) is flushed every 1000 rows, periods.csv every row.
    CsvOptions run_csv_options(const bool append, const unsigned int flush_every)
    {
      CsvOptions options;
      options.append      = append;
      options.in_place    = true;
      options.flush_every = flush_every;
      return options;
    }

    struct RunCsvFiles
    {
      RunCsvFiles(const std::string &dir, const bool append)
        : trace(dir + "/trace.csv", trace_csv_columns(), run_csv_options(append, 1000))
        , periods(dir + "/periods.csv", period_csv_columns(), run_csv_options(append, 1))
      {}
      CsvWriter trace, periods;
    };

    // The run's rows into the files (and its period records into the
    // outcome); with `verbose`, its progress on the console.
    void connect_outputs(AdaptationRun &run, RunCsvFiles &files, std::vector<PeriodRecord> &periods,
                         const bool verbose)
    {
      run.on_trace_row = [&files](const TraceRow &row) { write_trace_row(files.trace, row); };
      run.on_period    = [&files, &periods](const PeriodRecord &r) {
        write_period_row(files.periods, r);
        periods.push_back(r);
      };
      if (verbose)
        run.on_progress = [](const RunProgress &p) {
          console() << "  t = " << std::fixed << std::setprecision(1) << p.t << " / " << p.end_time
                    << " s, x_C/L = " << std::setprecision(3) << p.slider_x_over_L << ", amplitude "
                    << p.amplitude_over_h << " h, " << std::setprecision(0) << p.steps_per_second << " steps/s"
                    << std::endl
                    << std::defaultfloat;
        };
    }

    // --animate: the run up to the animation window, then frame by frame
    // to the end, each frame into animation.pvd.
    RunResult run_with_animation(AdaptationRun &run, const std::string &dir, const double end_time)
    {
      const double t_first = std::max(0., end_time - animation_window);
      RunResult result     = run.run_until(t_first);
      VtkAnimationWriter animation(dir, 1.);
      for (long k = 0; result.status == RunStatus::completed; ++k)
        {
          const double t_frame = t_first + k / animation_rate;
          if (t_frame > end_time + 1e-12)
            break;
          const RunResult part = run.run_until(t_frame);
          result.status        = part.status;
          result.message       = part.message;
          result.n_steps += part.n_steps;
          result.t_end = part.t_end;
          if (part.status != RunStatus::completed)
            break;
          animation.write(make_animation_frame(run.stepper()));
        }
      animation.finish();
      return result;
    }

    // checkpoint.bin: how the run was asked for, where its files end, its
    // period records and its state. The files are flushed first, so the
    // sizes it records are on disk.
    void write_checkpoint(SimulationRun &r, const AdaptationRun &run, RunCsvFiles &files, const std::uint64_t n_steps)
    {
      files.trace.flush();
      files.periods.flush();
      RunDescription d;
      d.scene_file      = r.scene_file;
      d.overrides       = r.common.overrides;
      d.case_name       = r.the_case ? r.the_case->name : std::string();
      d.scene_hash      = scene_content_hash(r.scene_file, d.overrides, d.case_name);
      d.setting         = r.outcome.setting;
      d.end_time        = r.outcome.scene.time_stepping.end_time;
      d.why             = r.outcome.why;
      d.identity        = run_identity(r.command_label, r.outcome.setting, r.timeless_scene_text);
      d.identity_digest = fnv1a(d.identity);
      d.scene_text      = r.scene_text;
      d.trace_bytes     = std::filesystem::file_size(files.trace.path());
      d.period_bytes    = std::filesystem::file_size(files.periods.path());
      extend_digest(files.trace.path(), r.trace_digest, d.trace_bytes);
      extend_digest(files.periods.path(), r.period_digest, d.period_bytes);
      d.trace_digest  = r.trace_digest.hash;
      d.period_digest = r.period_digest.hash;
      d.n_steps       = r.saved.n_steps + n_steps;
      d.wall_seconds  = r.saved.wall_seconds + elapsed_seconds(r.start);
      d.periods       = r.outcome.periods;
      CheckpointWriter out;
      save_description(out, d);
      run.save(out);
      write_file_atomically(r.outcome.dir + "/checkpoint.bin", checkpoint_file_bytes(out.bytes()));
    }

    // The run in pieces of --checkpoint-every, each followed by a
    // checkpoint; one piece without it. The trace is the same either way.
    RunResult run_in_pieces(SimulationRun &r, AdaptationRun &run, RunCsvFiles &files)
    {
      const double end_time = r.outcome.scene.time_stepping.end_time;
      const double every    = r.options.checkpoint_every.value_or(0.);
      const double eps      = 1e-9 * r.outcome.setting.time_step;
      double t_stop         = every > 0. ? (std::floor(run.state().t / every + 1e-9) + 1.) * every : end_time;
      RunResult result;
      while (true)
        {
          t_stop                = std::min(t_stop, end_time);
          const RunResult piece = run.run_until(t_stop);
          result.status         = piece.status;
          result.message        = piece.message;
          result.n_steps += piece.n_steps;
          result.t_end           = piece.t_end;
          result.slider_x_over_L = piece.slider_x_over_L;
          result.max_solver_iterations = std::max(result.max_solver_iterations, piece.max_solver_iterations);
          if (piece.status != RunStatus::completed)
            break;
          if (every > 0.)
            write_checkpoint(r, run, files, result.n_steps);
          if (t_stop >= end_time - eps)
            break;
          t_stop += every;
        }
      run.finish_trace();
      return result;
    }

    // summary.md: settings, cost, status and the verdict, against the
    // case's published behaviour where the run keeps the case as it is.
    std::string summary_text(const SimulationRun &r)
    {
      const Scene &scene          = r.outcome.scene;
      const SimulationCase *the_case = r.the_case;
      const RunResult &result     = r.outcome.result;
      const double wall           = r.outcome.wall_seconds;
      std::ostringstream summary;
      summary << "# simulate: scene `" << scene.name << "`" << (the_case ? ", case `" + the_case->name + "`" : "") << "\n\n";
      if (the_case && !r.modified.empty())
        {
          summary << "- Case: " << the_case->name << ", modified: ";
          for (std::size_t i = 0; i < r.modified.size(); ++i)
            summary << (i ? "; " : "") << r.modified[i];
          summary << ".\n- Not compared with the published behaviour (" << the_case->published
                  << "): the run changes parameters the case fixes.\n";
        }
      else if (the_case)
        {
          summary << "- Case: " << the_case->description << ".\n- Published: " << the_case->published << ".\n";
          const std::string differs = disagreements(r.outcome.verdict, the_case->expected);
          summary << "- Against the published behaviour: " << (differs.empty() ? "agrees on every stated feature" : "differs: " + differs) << ".\n";
        }
      const std::string &why = r.outcome.why;
      summary << "- Model: " << r.outcome.setting.label() << ".\n"
              << (why.empty() ? "" : "- Chosen by --model auto:\n\n```\n" + why + "\n```\n\n")
              << (r.resuming ? "- Resumed from the checkpoint in this folder (" + std::to_string(r.saved.n_steps) +
                                 " steps done before).\n"
                             : std::string())
              << (r.options.checkpoint_every ? "- Checkpoint every " + std::to_string(*r.options.checkpoint_every) +
                                                 " s simulated: checkpoint.bin (resume with `beamslider simulate --resume " +
                                                 r.outcome.dir + "`).\n"
                                             : std::string())
              << "- Simulated " << result.t_end << " s of " << scene.time_stepping.end_time << " s in " << wall << " s wall ("
              << (wall > 0 ? result.n_steps / wall : 0.) << " steps/s).\n"
              << "- Status: " << to_string(result.status) << (result.message.empty() ? "" : ": " + result.message) << ".\n"
              << "- Verdict: " << r.outcome.verdict.line << ".\n"
              << "\nFiles: trace.csv, periods.csv" << (r.options.animate ? ", animation.pvd" : "") << ", trace.png.\n";
      return summary.str();
    }

    // trace.png; none of an interrupted run: the user asked it to stop.
    void draw_trace_chart(EarlyPlot &chart, const SimulationRun &r)
    {
      if (r.outcome.result.status == RunStatus::interrupted)
        return;
      std::ostringstream title;
      title << r.outcome.scene.name << (r.the_case ? " / " + r.the_case->name : std::string()) << " ("
            << r.outcome.setting.label() << ")";
      chart.draw({r.outcome.dir, title.str(), std::to_string(r.outcome.scene.beam.thickness)});
    }
  } // namespace

  SimulationOutcome run_simulation(const CommonOptions &given_common, const SimulateOptions &given_options,
                                   const bool verbose)
  {
    // --resume DIR: the scene, overrides, case and model come from DIR's
    // checkpoint; the run continues from its state into the same files.
    SimulationRun r;
    r.common   = given_common;
    r.options  = given_options;
    r.resuming = !r.options.resume_dir.empty();
    if (r.resuming)
      {
        load_checkpoint_to_resume(r);
        check_checkpoint_is_folders_run(r);
      }
    check_simulate_options(r.options);
    read_simulation_scene(r);
    if (r.options.checkpoint_every)
      check_checkpoint_interval(r);
    describe_run(r);
    const Scene &scene     = r.outcome.scene;
    const std::string &dir = r.outcome.dir =
      prepare_output_dir(r.common, scene, r.command_label, r.resuming ? RunRecord::append : RunRecord::replace);
    // The chart's Python starts now and loads matplotlib while the run
    // computes; it draws once the CSV files are complete.
    EarlyPlot chart("plot_trace.py");

    choose_model(r);
    const ModelSetting &setting = r.outcome.setting;
    std::unique_ptr<BeamSystem> beam = make_beam_model(scene, setting);
    const double end_time = scene.time_stepping.end_time;
    console() << "simulate " << scene.name << (r.the_case ? " --case " + r.the_case->name : std::string()) << ": "
              << setting.label() << ", " << end_time << " s (" << std::llround(end_time / setting.time_step)
              << " steps), output in " << dir << std::endl;
    RunOptions run_options        = RunOptions::from_scene(scene, setting.time_step);
    run_options.progress_interval = std::max(1., end_time / 20.);
    require_stable_time_step(setting, *beam);
    AdaptationRun run(scene, *beam, run_options);
    if (r.resuming)
      restore_checkpointed_run(r, run);

    RunCsvFiles files(dir, r.resuming);
    connect_outputs(run, files, r.outcome.periods, verbose);
    r.start          = std::chrono::steady_clock::now();
    RunResult &result = r.outcome.result;
    result = r.options.animate ? run_with_animation(run, dir, end_time) : run_in_pieces(r, run, files);
    r.outcome.wall_seconds = elapsed_seconds(r.start);
    files.trace.close();
    files.periods.close();

    r.outcome.verdict = case_verdict(r.outcome.periods, result, trace_thresholds(scene));
    const std::string summary = summary_text(r);
    write_text_file(dir + "/summary.md", summary);
    if (!ends_in_a_result(result.status))
      std::cerr << "simulate: " << to_string(result.status) << ": " << result.message << std::endl;
    draw_trace_chart(chart, r);
    if (verbose)
      console() << summary;
    return std::move(r.outcome);
  }

  int run_simulate(const CommonOptions &common, const SimulateOptions &options)
  {
    const SimulationOutcome outcome = run_simulation(common, options);
    const RunResult &result         = outcome.result;
    // Reaching a support is a physical outcome of the scene (the run stops
    // there by design); a failing solver, a non-finite or unphysical state is
    // not; an interrupted run exits as the signal says (130, 143).
    if (result.status == RunStatus::interrupted)
      return interruption_exit_code();
    return ends_in_a_result(result.status) ? 0 : 1;
  }
} // namespace beamslider
