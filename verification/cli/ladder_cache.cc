// The cache of the model choice's error ladder, see ladder_cache.h.
#include "verification/cli/ladder_cache.h"

#include "io/csv_writer.h"
#include "io/console.h"
#include "verification/studies/model_choice.h"

#include <filesystem>
#include <fstream>
#include <sstream>

namespace beamslider
{
  namespace
  {
    const std::vector<std::string> cache_columns = {"rung",        "family",       "n_modes",    "static_corrections", "ritz_blocks", "n_elements",
                                                    "integrator",  "time_step_s",  "damped_modes", "theta", "reference",
                                                    "cost_units",  "final_x_median", "w1",         "w1_high", "refined_alike"};

    // The cache, or an empty vector if there is none or it is not ours.
    std::vector<LadderChoiceRow> read_cache(const std::string &path)
    {
      std::vector<LadderChoiceRow> rows;
      std::ifstream in(path);
      std::string line;
      if (!in || !std::getline(in, line) || line != CsvWriter::line(cache_columns))
        return rows;
      while (std::getline(in, line))
        {
          const auto c = CsvWriter::cells(line);
          if (c.size() != cache_columns.size())
            return {};
          LadderChoiceRow r;
          r.rung                = c[0];
          r.model.family        = c[1];
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
      return rows;
    }

    // 17 significant digits: a double read back from the cache is the one written.
    std::string number(const double x) { return CsvWriter::cell(x, 17); }

    void write_cache(const std::string &path, const std::vector<LadderChoiceRow> &rows)
    {
      CsvWriter cache(path, cache_columns);
      for (const auto &r : rows)
        cache.row({r.rung, r.model.family, CsvWriter::cell(r.model.n_modes),
                   CsvWriter::cell(r.model.n_static_corrections), CsvWriter::cell(r.model.ritz_blocks),
                   CsvWriter::cell(r.model.n_elements),
                   r.model.integrator, number(r.model.time_step), CsvWriter::cell(r.model.damped_modes),
                   number(r.model.theta), r.reference ? "1" : "0", number(r.cost_units), number(r.final_x_median), number(r.w1),
                   number(r.w1_high), r.refined_alike ? "1" : "0"});
      cache.close();
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
    std::vector<LadderChoiceRow> rows = read_cache(path);
    std::ostringstream log;
    if (!rows.empty())
      log << "model choice from the cached error ladder " << path << ":\n";
    else if (n_ranks > 1)
      throw InputError("--model auto under mpirun needs the scene's error ladder cached: run the command once without "
                       "mpirun (or `simulate --model auto`), which computes it and caches it in " + cache_dir);
    else
      {
        const ChoiceLadder ladder = run_ladder_for_choice(scene);
        rows                      = ladder.rows;
        std::filesystem::create_directories(cache_dir);
        write_cache(path, rows);
        log << "model choice from the error ladder just computed (cached in " << path << "):\n";
        for (const std::string &verdict : ladder.check_verdicts)
          log << "  " << verdict << "\n";
      }
    const ModelChoice choice = tolerance ? choose_from_ladder(scene, rows, *tolerance) : choose_from_ladder(scene, rows);
    why                      = log.str() + choice.why;
    return choice.model;
  }
} // namespace beamslider
