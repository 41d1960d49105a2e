// The files of the prescribed-position sweep, see pcs_files.h.
#include "verification/report/pcs_files.h"
#include "io/input_file.h"

#include "runs/adaptation_run.h"
#include "io/csv_writer.h"
#include "io/console.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <ostream>
#include <sstream>

namespace beamslider
{
  namespace
  {
    // A sweep's files, opened when its study starts and written as its
    // results come (the study calls the observer one call at a time).
    class PcsSweepFiles
    {
    public:
      explicit PcsSweepFiles(const std::string &dir) : dir_(dir) {}

      // Rows to the files, progress lines to the console.
      PcsSweepObserver observer()
      {
        PcsSweepObserver o;
        o.on_start        = [this](const PcsStudy &study) { open(study); };
        o.on_point        = [this](const PcsPoint &p) { write_point(p); };
        o.on_free_period  = [this](const PeriodRecord &r) { write_period_row(*free_periods_, r); };
        o.on_free_run_end = [this](const RunResult &) { free_periods_.reset(); };
        o.on_progress     = [](const std::string &line) { console() << line << std::endl; };
        return o;
      }

      // Whether each run reached its end: pcs.csv holds the positions a
      // branch reached, which its rows alone cannot tell from a complete
      // branch.
      void write_run_rows(const PcsStudy &study)
      {
        for (const PcsBranch *branch : {&study.up, &study.down})
          runs_->row({to_string(branch->direction), to_string(branch->last_run.status),
                      CsvWriter::cell(branch->points.size()), std::to_string(study.positions_planned),
                      CsvWriter::cell(branch->last_run.t_end)});
        if (study.with_free_run)
          runs_->row({"free", to_string(study.free_run.status), "", "", CsvWriter::cell(study.free_run.t_end)});
      }

      // The files of a finished study, as if its results came now: each
      // branch's points in its order, up first.
      void write_all(const PcsStudy &study)
      {
        open(study);
        for (const PcsBranch *branch : {&study.up, &study.down})
          for (const PcsPoint &p : branch->points)
            write_point(p);
        if (study.with_free_run)
          {
            for (const PeriodRecord &r : study.free_periods)
              write_period_row(*free_periods_, r);
            free_periods_->close();
          }
        write_run_rows(study);
        pcs_->close();
        runs_->close();
      }

    private:
      // resonance.csv whole; pcs.csv and runs.csv in place (rows as
      // positions finish: kept by a stopped sweep); free_periods.csv for
      // the free run.
      void open(const PcsStudy &study)
      {
        if (!study.resonance.empty())
          write_resonance_curve(study.resonance);
        CsvOptions in_place;
        in_place.in_place = true;
        pcs_.emplace(dir_ + "/pcs.csv",
                     std::vector<std::string>{"x_over_L", "direction", "amplitude_over_h", "mean_fx_N",
                                              "amplitude_std_over_h", "mean_fx_std_N", "n_periods", "t_end_s",
                                              "mean_fx_ci95_N"},
                     in_place);
        runs_.emplace(dir_ + "/runs.csv",
                      std::vector<std::string>{"run", "status", "positions", "positions_planned", "t_end_s"}, in_place);
        if (study.with_free_run)
          free_periods_.emplace(dir_ + "/free_periods.csv", period_csv_columns());
      }

      void write_resonance_curve(const std::vector<ResonancePoint> &curve) const
      {
        CsvWriter csv(dir_ + "/resonance.csv", {"x_over_L", "amplitude_over_h"});
        for (const ResonancePoint &r : curve)
          csv.row({CsvWriter::cell(r.x_over_L),
                   std::isfinite(r.amplitude_over_h) ? CsvWriter::cell(r.amplitude_over_h) : ""});
      }

      void write_point(const PcsPoint &p)
      {
        pcs_->row({CsvWriter::cell(p.x_over_L), to_string(p.direction), CsvWriter::cell(p.amplitude_over_h),
                   CsvWriter::cell(p.mean_fx), CsvWriter::cell(p.amplitude_std_over_h), CsvWriter::cell(p.mean_fx_std),
                   std::to_string(p.n_periods), CsvWriter::cell(p.t_end), CsvWriter::cell(p.mean_fx_ci95)});
      }

      std::string dir_;
      std::optional<CsvWriter> pcs_, runs_, free_periods_;
    };
  } // namespace

  PcsStudy run_pcs_sweep_into(const Scene &scene, const PcsStudySettings &settings, const std::string &dir)
  {
    PcsSweepFiles files(dir);
    PcsStudy study = run_pcs_sweep(scene, settings, files.observer());
    files.write_run_rows(study);
    return study;
  }

  PcsStudy run_pcs_sweep_in_memory(const Scene &scene, const PcsStudySettings &settings)
  {
    PcsSweepObserver progress;
    progress.on_progress = [](const std::string &line) { console() << line << std::endl; };
    return run_pcs_sweep(scene, settings, progress);
  }

  void write_pcs_files(const PcsStudy &study, const std::string &dir)
  {
    PcsSweepFiles(dir).write_all(study);
  }

  std::vector<PcsPoint> read_pcs_csv(const std::string &path)
  {
    std::istringstream in(read_option_file(path, "--against: no readable pcs.csv"));
    std::string line;
    std::getline(in, line);
    std::vector<std::string> header;
    {
      std::stringstream row(line);
      for (std::string cell; std::getline(row, cell, ',');)
        header.push_back(cell);
    }
    std::map<std::string, std::size_t> column;
    for (const char *name : {"x_over_L", "direction", "amplitude_over_h", "mean_fx_N", "mean_fx_ci95_N"})
      {
        const auto it = std::find(header.begin(), header.end(), name);
        if (it == header.end())
          throw InputError("--against: '" + path + "' is not a sweep's pcs.csv (no column " + name + ")");
        column[name] = it - header.begin();
      }
    std::vector<PcsPoint> points;
    for (unsigned int row_number = 2; std::getline(in, line); ++row_number)
      {
        std::vector<std::string> cells;
        std::stringstream row(line);
        for (std::string cell; std::getline(row, cell, ',');)
          cells.push_back(cell);
        try
          {
            if (cells.size() != header.size())
              throw std::invalid_argument("wrong number of cells");
            PcsPoint p;
            p.x_over_L         = std::stod(cells[column["x_over_L"]]);
            const std::string d = cells[column["direction"]];
            if (d != "up" && d != "down")
              throw std::invalid_argument("direction '" + d + "'");
            p.direction        = d == "up" ? SweepDirection::up : SweepDirection::down;
            p.amplitude_over_h = std::stod(cells[column["amplitude_over_h"]]);
            p.mean_fx          = std::stod(cells[column["mean_fx_N"]]);
            p.mean_fx_ci95     = std::stod(cells[column["mean_fx_ci95_N"]]);
            points.push_back(p);
          }
        catch (const std::exception &e)
          {
            throw InputError("--against: row " + std::to_string(row_number) + " of '" + path +
                             "' cannot be read (" + e.what() + ")");
          }
      }
    return points;
  }

  void write_pcs_comparison(const PcsComparison &comparison, const std::string &dir)
  {
    CsvWriter positions(dir + "/comparison.csv",
                        {"direction", "x_over_L", "amplitude_over_h", "other_amplitude_over_h",
                         "amplitude_relative_difference", "mean_fx_N", "mean_fx_ci95_N", "other_mean_fx_N",
                         "other_mean_fx_ci95_N", "fx_intervals_overlap"});
    for (const auto &p : comparison.positions)
      positions.row({to_string(p.direction), CsvWriter::cell(p.x_over_L), CsvWriter::cell(p.amplitude),
                     CsvWriter::cell(p.other_amplitude), CsvWriter::cell(p.amplitude_relative_difference),
                     CsvWriter::cell(p.fx), CsvWriter::cell(p.fx_ci95), CsvWriter::cell(p.other_fx),
                     CsvWriter::cell(p.other_fx_ci95), p.fx_intervals_overlap ? "1" : "0"});
    CsvWriter crossings(dir + "/crossings.csv",
                        {"sweep", "direction", "x_over_L", "x_low_over_L", "x_high_over_L", "stable", "resolved"});
    for (const auto *branch : {&comparison.up, &comparison.down})
      for (const auto &[name, list] : {std::pair("this", &branch->crossings), std::pair("other", &branch->other_crossings)})
        for (const auto &c : *list)
          crossings.row({name, to_string(branch->direction), CsvWriter::cell(c.x_over_L),
                         CsvWriter::cell(c.x_low_over_L), CsvWriter::cell(c.x_high_over_L), c.stable ? "1" : "0",
                         c.resolved ? "1" : "0"});
  }
} // namespace beamslider
