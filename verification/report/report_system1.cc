// Report section 7: the seed's System 1 facts. The seed's Table 1 is missing
// from our copy, so meshes/system1.prm carries a set of unknown parameters
// IDENTIFIED by `beamslider identify` (verification/studies/system1_facts.h):
// one map per fact over the unknowns, each candidate scored by the facts'
// named criteria. This section states the facts and their criteria, runs
// each fact's scenario once on the scene as written (the identified set, ROM,
// one member) and gives each fact's verdict, score and reason. The search
// itself (grids, wall times, every candidate's scores) is `beamslider
// identify`'s identification.csv; its result is recorded in the scene's
// header and in doc/verification.md.
//
// Only for the scene named system1: the facts are statements about it.
//
// Files in <report>/system1/: facts.csv (one row per fact: scenario,
// verdict, score, reason), <fact>/map.csv (the run, in the map's format).
#include "io/csv_writer.h"
#include "io/output_file.h"
#include "verification/report/map_files.h"
#include "verification/report/report.h"
#include "io/console.h"
#include "verification/studies/operating_map.h"
#include "verification/studies/system1_facts.h"

#include <chrono>
#include <filesystem>
#include <sstream>

namespace beamslider
{
  void add_system1_section(Report &report, const Scene &scene, const bool /*full*/)
  {
    std::ostringstream &out = report.text;
    out << "## 7. The seed's System 1 facts\n\n";
    if (scene.name != "system1")
      {
        out << "The facts of this section are the seed's statements about its System 1; they apply to the scene "
               "`system1` only (`beamslider verify system1`).\n\n";
        return;
      }
    const auto start = std::chrono::steady_clock::now();
    console() << "  section 7: the seed's System 1 facts" << std::endl;

    // One candidate: the scene as written. A one-value axis that no fact
    // fixes (the restitution) makes each fact's run a one-cell map.
    MapGrid here;
    here.axes.push_back({"Contact/Restitution", "contact_restitution", {scene.contact.restitution}});
    MapSettings settings;
    settings.model.family = "rom";
    settings.n_members    = 1;
    bool complete         = true;
    const std::string dir = report.dir + "/system1";
    std::filesystem::create_directories(dir);
    const IdentificationResult r = identify_system1(
      report.scene_file, report.overrides, here, {}, settings, complete,
      [&](const System1Fact &fact, const MapGrid &grid, const std::vector<std::vector<MapMember>> &cells) {
        std::filesystem::create_directories(dir + "/" + fact.id);
        write_map_csv(dir + "/" + fact.id + "/map.csv", grid, cells);
      });

    out << "The seed's Table 1 is missing from our copy, so six parameters of System 1 are unknown: the friction "
           "coefficient, the restitution, the slider's centre-of-mass offset d, window width B and rotary inertia "
           "J_C, and the modal damping ratio. `meshes/system1.prm` holds a set **identified** (not measured) by "
           "`beamslider identify`: for each fact below, one map over the unknowns with the fact's scenario; each "
           "candidate scored by the facts' criteria (verification/studies/system1_facts.h; score = mean of the "
           "fact's conditions, 1 met, 0 not, a position falling linearly to 0 at three tolerances). The search and "
           "its result are in the scene's header and in doc/verification.md.\n\n"
        << "The six unknowns as this run used them (the identified set, unless --set changed one):\n\n| parameter | value |\n|---|---|\n"
        << "| friction coefficient μ | " << scene.contact.friction_coefficient << " |\n"
        << "| restitution e_N | " << scene.contact.restitution << " |\n"
        << "| centre-of-mass offset d | " << scene.slider.com_offset * 1e3 << " mm |\n"
        << "| window width B | " << scene.slider.window_width * 1e3 << " mm |\n"
        << "| rotary inertia J_C | " << scene.slider.inertia << " kg m² |\n"
        << "| modal damping ratio D | " << scene.damping_ratio * 100 << " % |\n\n"
        << "Each fact's scenario run once on the scene as written (ROM, one member; runs are chaotic, so a single "
           "run is one sample, not a distribution):\n\n"
        << "| fact | scenario | verdict | score | reason |\n|---|---|---|---|---|\n";
    CsvWriter csv(dir + "/facts.csv", {"id", "name", "overrides", "end_time_s", "pass", "score", "reason"});
    unsigned int n_pass = 0;
    for (std::size_t i = 0; i < r.fact_ids.size(); ++i)
      {
        const System1Fact &f = system1_fact(r.fact_ids[i]);
        std::string scenario;
        for (const std::string &o : f.overrides)
          scenario += (scenario.empty() ? "" : ", ") + o;
        const bool judged = r.judged[0][i];
        const bool pass   = judged && r.passes[0][i] == 1;
        n_pass += pass;
        out << "| " << f.name << " | " << scenario << ", " << f.end_time << " s | "
            << (!judged ? "not run" : pass ? "reproduced" : "**not reproduced**") << " | "
            << (judged ? fixed(r.scores[0][i], 2) : "—") << " | " << r.reasons[0][i] << " |\n";
        csv.row({f.id, f.name, scenario, CsvWriter::cell(f.end_time, 6), judged ? (pass ? "1" : "0") : "",
                 judged ? CsvWriter::cell(r.scores[0][i], 4) : "", r.reasons[0][i]});
      }
    csv.close();
    out << "\n" << n_pass << " of " << r.fact_ids.size() << " facts reproduced; total score "
        << fixed(r.total(0), 2) << " of " << r.fact_ids.size() << (complete ? "" : " (interrupted: the facts not run have no verdict)")
        << ". Section time " << seconds_since(start) << ". Files: system1/facts.csv, system1/<fact>/map.csv.\n\n";
  }
} // namespace beamslider
