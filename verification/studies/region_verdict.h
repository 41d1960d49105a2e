// The verdict across the signature-move region: the error ladder's
// question (how far does a reduced model land from the FE beam?) asked at
// several operating points (excitation frequency and level) at once, each
// with a reference that proves its own convergence (convergence_check.h).
//
// At every point the quick ladder's models run as ensembles from the
// scene's start: the published ROM (the scene's N and Δt), N = 10 (Δt/2),
// N = 20 (Δt/4, checked in N against N = 30 at the explicit scheme's step,
// whose members are the N = 30 column), the front's N = 15 and 6 + 4 static
// corrections, each explicit ROM also at Δt/2, and the scene's FE model
// (checked in Δt: Δt/2 beside it, halved further until two steps end
// alike). All members of all points run as one list, longest first, then
// the checks' later rounds. The published cases run the same way, each
// case a site (published_case_sites).
//
// This study computes and returns results; it writes no files
// (verification/report/report_region.h formats them).
#pragma once

#include "scene/scene.h"
#include "verification/studies/convergence_check.h"
#include "verification/studies/error_ladder.h"

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace beamslider
{
  struct OperatingPoint
  {
    double frequency_hz      = 0; // f_ex [Hz]
    double acceleration_m_s2 = 0; // â [m/s²]
    std::string label() const;    // "124 Hz / 14 m/s²"
  };

  // Six points spread over the signature-move region of the scene's
  // operating-range map (ROM N = 5 from x_C/L = 0.3: signature moves from
  // 113 to 136 Hz and from 7.9 to 21 m/s², report section 6), the scene's
  // own excitation among them.
  std::vector<OperatingPoint> signature_move_region(const Scene &scene);

  // The scene with its excitation at `point`.
  Scene at_point(const Scene &scene, const OperatingPoint &point);

  // The models of every point: the quick ladder's (default_ladder), the FE
  // reference last (`reference` is set to its index).
  std::vector<LadderRung> region_rungs(const Scene &scene, std::size_t &reference);

  // A place a study runs its ladder: its name in the tables and the scene
  // (its end time set).
  struct StudySite
  {
    std::string label;
    Scene scene;
  };
  // The rungs at one site and the index of its reference.
  using SiteRungs = std::function<std::vector<LadderRung>(const Scene &, std::size_t &)>;

  // Every site's rungs (`rungs_of`) and checks as one list of member runs
  // (`runner`, or threads), then the checks' rounds (`rounds`, in step over
  // the ranks by `share`; run_convergence_checks): a checked ladder per site.
  // Then the class rounds, by `rounds` too: every rung (the reference at the
  // step its check took) whose members do not decide its majority class
  // (majority_decided) gets more members, round by round, up to the
  // ceiling; the checks are judged on the first members.
  std::vector<LadderStudy> run_sites(const std::vector<StudySite> &sites, const SiteRungs &rungs_of,
                                     unsigned int members, const MemberGroupRunner &runner = {},
                                     const MemberGroupRunner &rounds = {},
                                     const std::function<unsigned long(unsigned long)> &share = {});
  // The other MPI ranks' part of run_sites.
  void work_on_sites(const std::vector<StudySite> &sites, const SiteRungs &rungs_of, unsigned int members,
                     const std::function<void(const std::vector<MemberGroup> &)> &work,
                     const std::function<unsigned long(unsigned long)> &share);

  // The published cases as sites: each as `simulate --case` reads it (the
  // scene file, the case's overrides, the user's), at its own end time.
  std::vector<StudySite> published_case_sites(const std::string &scene_file, const std::vector<std::string> &overrides);
  // The models the published cases run: the published ROM, the quick
  // ladder's front candidates (N = 15 and the full front's pick, 6 + 4
  // static corrections, each also at Δt/2) and the FE reference, proving
  // itself, last.
  std::vector<LadderRung> case_rungs(const Scene &scene, std::size_t &reference);

  // How many of a model's members took each outcome class (the trace
  // analysis's names; members without a valid analysis count for none).
  using ClassCounts = std::map<std::string, unsigned int>;
  ClassCounts class_counts(const std::vector<EnsembleMember> &members);

  // The class most members took; "split" when two classes tie for most, "–"
  // with no member.
  std::string majority_class(const ClassCounts &counts);

  // Whether a model's members decide its majority class: the exact one-sided
  // binomial (sign) test of "the majority class is taken with probability at
  // most ½". Its p-value is P(X ≥ k | n, ½) for k of the n classified
  // members in the majority class (1 with no member, or two classes tied);
  // decided when it is below class_decision_level, i.e. with 90 %
  // confidence that the class is more than a coin's toss: 4 of 4 decide it
  // (p = 1/16), 3 of 4 do not (5/16), 7 of 8 do (0.035), 6 of 8 do not
  // (0.145), 9 of 12 do (0.073), 11 of 16 do not (0.105).
  double majority_p_value(const ClassCounts &counts);
  constexpr double class_decision_level = 0.1;
  bool majority_decided(const ClassCounts &counts);
  // A rung whose members do not decide its class (run_sites) runs
  // class_members_step more members (the next indices, start x_C/L + m·ε)
  // at a time, until they do or it has class_members_ceiling.
  constexpr unsigned int class_members_step = 4, class_members_ceiling = 16;

  // Whether a model ends alike with the reference at a point: both have a
  // majority class, the same one, and their end positions end alike
  // (convergence_check.h's ends_alike: indistinguishable, or closer than the
  // resolution). A model or reference whose members split evenly is not
  // alike: its class is undecided with these members. End positions alone
  // would call a model alike whose members relax where the reference's make
  // the signature move, when both classes end near the same x_C.
  bool alike_with_reference(const SampleComparison &end_positions, const ClassCounts &model,
                            const ClassCounts &reference);

  // Whether the rung converged in N and its check's larger basis (N = 30)
  // both end apart from the reference (ends_alike): more modes do not bring
  // the ROM to the reference at this site.
  bool basis_gap(const LadderStudy &ladder);

  // Which difference between ROM and FE moves the end state where
  // basis_gap holds, by two ROMs run beside them:
  //   - every bending mode of the FE mesh, stepped as the site's reference
  //     is (implicit, its θ and Δt), damping the scene's N modes as the FE
  //     does: it differs from the FE only in its form (no axial inertia, the
  //     quasi-static cubic membrane, the contact on the modal sum);
  //   - the N check's larger basis (`larger_basis`, N = 30 at its own
  //     explicit step) stepped with the reference's θ instead of the
  //     explicit midpoint rule: it differs from the region's N = 30 only in
  //     the scheme's numerical damping of the modes that ring after each
  //     impact (θ > ½ damps a resolved mode by about (θ − ½)ωΔt).
  std::vector<LadderRung> model_form_probes(const Scene &scene, const ModelSetting &reference,
                                            const ModelSetting &larger_basis);

  struct RegionStudy
  {
    std::vector<OperatingPoint> points;
    std::vector<LadderStudy> ladders; // one per point, with its checks
    // At each point where basis_gap holds (its index first): the two
    // model_form_probes and the point's reference, the reference last.
    std::vector<std::pair<std::size_t, LadderStudy>> model_form;
  };

  // run_sites at the points, each with the region_rungs, then the
  // model_form_probes where basis_gap holds (by `rounds`, as a later round).
  RegionStudy run_region(const Scene &scene, const std::vector<OperatingPoint> &points, double end_time,
                         unsigned int members, const MemberGroupRunner &runner = {},
                         const MemberGroupRunner &rounds = {},
                         const std::function<unsigned long(unsigned long)> &share = {});

  // The other MPI ranks' part of run_region, given how they compute a list
  // of member groups (`work`) and rank 0's mask (`share`).
  void work_on_region(const Scene &scene, const std::vector<OperatingPoint> &points, double end_time,
                      unsigned int members, const std::function<void(const std::vector<MemberGroup> &)> &work,
                      const std::function<unsigned long(unsigned long)> &share);
} // namespace beamslider
