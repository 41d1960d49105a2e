// The checkpoints of `beamslider simulate`: checkpoint.bin written as the
// run goes (--checkpoint-every), and a run resumed from it (--resume DIR).
#include "io/checkpoint.h"
#include "io/input_file.h"
#include "io/output_file.h"
#include "io/console.h"
#include "scene/scene.h"
#include "numerics/elapsed.h"
#include "runs/adaptation_run.h"
#include "verification/cli/commands.h"
#include "verification/cli/simulate_run.h"
#include "verification/studies/fe_rom_study.h"
#include "verification/studies/simulation.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <sys/stat.h>
#include <unistd.h>
#include <algorithm>
#include <sstream>
#include <utility>

namespace beamslider
{
  namespace
  {
    using internal::FileDigest;
    using internal::RunDescription;

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
  } // namespace

  namespace internal
  {
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
  } // namespace internal
} // namespace beamslider
