// The verdict across the signature-move region (verification/studies/
// region_verdict.h) as the full report's headline: one row per operating
// point with its converged FE reference and the evidence (the step it
// needed, its end state and its half step's), and each reduced model's end
// state and W₁ to that reference. Files written into the report folder:
//   member_runs.region.csv, member_runs.region.check-1.csv, …
//                     every finished member (the resume record)
//   region.csv        one row per point and model: point (frequency,
//                     acceleration), then the columns published_cases.csv
//                     has after its case (below; one writer for both)
//   region_convergence.csv  every point's checks (report_convergence.h)
#pragma once

#include "scene/scene.h"
#include "verification/studies/region_verdict.h"

#include <string>

namespace beamslider
{
  struct RegionRunSettings
  {
    double end_time      = 40.; // [s] simulated per member
    unsigned int members = 4;
    std::string progress_prefix;
    // Where FE members are shared with the ladder and later reports
    // (member_files.h, share_fe_members); "": not shared.
    std::string shared_members_root;
  };

  // Runs the region study into `dir` (over the MPI ranks under mpirun, else
  // the cores) and returns its Markdown: the table, the summary the README
  // quotes, the checks' evidence. Throws MemberRunsStopped when stopped.
  std::string run_and_describe_region(const std::string &dir, const Scene &scene, const RegionRunSettings &settings);

  // The region's summary, as the README quotes it: each model's W₁ range
  // over the points and at how many it ends alike with the reference (and
  // moves at Δt/2), the first model that meets the reference everywhere if
  // any, and the points where the ROM converged in N and its check with
  // more modes both end apart from the reference (there the basis is not
  // what separates ROM and FE).
  std::string region_summary(const RegionStudy &study);

  // The other MPI ranks' part.
  void work_on_region_members(const Scene &scene, const RegionRunSettings &settings);

  // The published cases (published_case_sites) with case_rungs, run into
  // `dir` as the region is (settings.end_time unused: each case's own), and
  // their Markdown: a row per case with the classes of every model and of
  // the checked reference, and per model the cases whose class it takes.
  // Files: published_cases.csv (one row per case and model: step, modes,
  // corrections, members, final x_C/L median/min/max, final amplitude
  // median, W₁ to the reference with interval and spread, distinguishable,
  // classes, majority class, alike (region_verdict.h's
  // alike_with_reference), whether it moved at Δt/2, the reference's
  // convergence), published_cases_convergence.csv, member_runs.cases.csv.
  std::string run_and_describe_cases(const std::string &dir, const std::vector<StudySite> &sites,
                                     const RegionRunSettings &settings);
  void work_on_case_members(const std::vector<StudySite> &sites, const RegionRunSettings &settings);
} // namespace beamslider
