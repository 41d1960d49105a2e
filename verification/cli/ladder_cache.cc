// The cache of the model choice's error ladder, see ladder_cache.h.
#include "verification/cli/ladder_cache.h"

#include "io/console.h"
#include "io/csv_writer.h"
#include "io/input_file.h"
#include "io/output_file.h"
#include "numerics/state_bytes.h"
#include "runtime/build_info.h"
#include "verification/studies/model_choice.h"

#include <algorithm>
#include <filesystem>
#include <sstream>

namespace beamslider
{
  namespace
  {
    const std::vector<std::string> cache_columns = {"rung",        "family",       "n_modes",    "static_corrections", "ritz_blocks", "n_elements",
                                                    "integrator",  "time_step_s",  "damped_modes", "theta", "reference",
                                                    "cost_units",  "final_x_median", "w1",         "w1_high", "refined_alike"};

    // The cache's first line: what it is, its format, the build that wrote
    // it and the checksum of everything below (the CSV). A cache from
    // another format or build, or with any byte changed, is not used.
    constexpr unsigned int cache_format = 2;
    // The title up to this build's name: the same in every cache this build
    // and format write, whatever their content.
    std::string cache_title_prefix()
    {
      return "# beamslider model-choice cache, format " + std::to_string(cache_format) + ", build " +
             build_revision() + " (";
    }
    std::string cache_title(const std::string &body)
    {
      std::ostringstream title;
      title << cache_title_prefix() << build_info().built_for << "), fnv1a " << std::hex << fnv1a(body);
      return title.str();
    }

    // The cache's rows, or none and in `why` the reason it is not used.
    std::vector<LadderChoiceRow> read_cache(const std::string &path, std::string &why)
    {
      std::string text;
      try
        {
          text = read_text_file_if_present(path);
        }
      catch (const FileReadError &e)
        {
          why = e.what(); // a FIFO, a folder, no permission: recomputed, never waited on
          return {};
        }
      if (text.empty())
        {
          why = "none cached";
          return {};
        }
      const auto first_end = text.find('\n');
      const std::string title = text.substr(0, first_end);
      const std::string body  = first_end == std::string::npos ? std::string() : text.substr(first_end + 1);
      if (title != cache_title(body))
        {
          why = title.rfind(cache_title_prefix(), 0) == 0 ? "its checksum does not match its content"
                  : "written by another build or format of beamslider, or damaged";
          return {};
        }
      std::istringstream in(body);
      std::string line;
      if (!std::getline(in, line) || line != CsvWriter::line(cache_columns))
        {
          why = "its columns are not this build's";
          return {};
        }
      std::vector<LadderChoiceRow> rows;
      try
        {
          while (std::getline(in, line))
            {
              const auto c = CsvWriter::cells(line);
              if (c.size() != cache_columns.size())
                throw std::invalid_argument("a row with " + std::to_string(c.size()) + " cells");
              LadderChoiceRow r;
              r.rung                       = c[0];
              r.model.family               = c[1];
              r.model.n_modes              = std::stoul(c[2]);
              r.model.n_static_corrections = std::stoul(c[3]);
              r.model.ritz_blocks          = std::stoul(c[4]);
              r.model.n_elements           = std::stoul(c[5]);
              r.model.integrator           = c[6];
              r.model.time_step            = std::stod(c[7]);
              r.model.damped_modes         = std::stoul(c[8]);
              r.model.theta                = std::stod(c[9]);
              r.reference                  = c[10] == "1";
              r.cost_units                 = std::stod(c[11]);
              r.final_x_median             = std::stod(c[12]);
              r.w1                         = std::stod(c[13]);
              r.w1_high                    = std::stod(c[14]);
              r.refined_alike              = c[15] == "1";
              rows.push_back(r);
            }
        }
      catch (const std::exception &e)
        {
          why = std::string("a cell that is not a number (") + e.what() + ")";
          return {};
        }
      const auto n_references = std::count_if(rows.begin(), rows.end(), [](const auto &r) { return r.reference; });
      if (n_references != 1)
        {
          why = std::to_string(n_references) + " reference rows instead of one";
          return {};
        }
      return rows;
    }

    // 17 significant digits: a double read back from the cache is the one written.
    std::string number(const double x) { return CsvWriter::cell(x, 17); }

    void write_cache(const std::string &path, const std::vector<LadderChoiceRow> &rows)
    {
      std::string body = CsvWriter::line(cache_columns) + "\n";
      for (const auto &r : rows)
        body += CsvWriter::line({r.rung, r.model.family, CsvWriter::cell(r.model.n_modes),
                                 CsvWriter::cell(r.model.n_static_corrections), CsvWriter::cell(r.model.ritz_blocks),
                                 CsvWriter::cell(r.model.n_elements), r.model.integrator, number(r.model.time_step),
                                 CsvWriter::cell(r.model.damped_modes), number(r.model.theta), r.reference ? "1" : "0",
                                 number(r.cost_units), number(r.final_x_median), number(r.w1), number(r.w1_high),
                                 r.refined_alike ? "1" : "0"}) +
                "\n";
      write_text_file(path, choice_cache_file_text(body));
    }

    // The quick ladder of `scene`, its progress on the console.
    ChoiceLadder run_ladder_for_choice(const Scene &scene)
    {
      std::size_t reference = 0;
      const auto rungs      = default_ladder(scene, LadderScope::quick, reference);
      console() << "--model auto: no cached error ladder for this scene; running it (" << rungs.size()
                << " models × " << choice_ladder_members << " members over " << choice_ladder_end_time
                << " s, a few minutes, the FE most of it) ..." << std::endl;
      return run_choice_ladder(scene, rungs, reference, [](const LadderRung &rung, std::size_t) {
        console() << "  " << rung.name << " (" << rung.model.label() << ")" << std::endl;
      });
    }
  } // namespace

  std::string choice_cache_file_text(const std::string &csv)
  {
    return cache_title(csv) + "\n" + csv;
  }

  std::string choice_cache_dir(const Scene &scene)
  {
    return (std::filesystem::path("reports") / scene.name / "model_choice").string();
  }

  ModelSetting choose_model(const Scene &scene, const std::optional<double> tolerance, const std::string &cache_dir,
                            std::string &why, const unsigned int n_ranks)
  {
    if (scene.solid.enabled())
      throw InputError("--model auto chooses on the beam's error ladder, which a solid scene (Solid/Continuum = '" +
                       scene.solid.continuum + "') does not have: use --model rom (the solid's reduced model) or "
                       "--model fe (the 1D beam)");
    const std::string path = cache_dir + "/ladder-" + scene_content_key(scene) + ".csv";
    std::string refused;
    std::vector<LadderChoiceRow> rows = read_cache(path, refused);
    std::ostringstream log;
    if (!rows.empty())
      log << "model choice from the cached error ladder " << path << ":\n";
    else if (n_ranks > 1)
      throw InputError("--model auto under mpirun needs the scene's error ladder cached (" + path + ": " + refused +
                       "): run the command once without mpirun (or `simulate --model auto`), which computes it and "
                       "caches it in " + cache_dir);
    else
      {
        if (refused != "none cached")
          console() << "--model auto: the cached error ladder " << path << " is not used (" << refused
                    << "); computing it again" << std::endl;
        const ChoiceLadder ladder = run_ladder_for_choice(scene);
        rows                      = ladder.rows;
        // The choice stands without the cache: a place it cannot be
        // written costs the next run the ladder again, not this run's result.
        std::string kept = "cached in " + path;
        try
          {
            std::filesystem::create_directories(cache_dir);
            write_cache(path, rows);
          }
        catch (const std::exception &e)
          {
            kept = "not cached: " + std::string(e.what());
            console() << "--model auto: the error ladder could not be cached (" << e.what()
                      << "); the next --model auto computes it again" << std::endl;
          }
        log << "model choice from the error ladder just computed ("
            << (refused != "none cached" ? "the cached one was not used: " + refused + "; " : std::string()) << kept
            << "):\n";
        for (const std::string &verdict : ladder.check_verdicts)
          log << "  " << verdict << "\n";
      }
    const ModelChoice choice = tolerance ? choose_from_ladder(scene, rows, *tolerance) : choose_from_ladder(scene, rows);
    why                      = log.str() + choice.why;
    return choice.model;
  }
} // namespace beamslider
