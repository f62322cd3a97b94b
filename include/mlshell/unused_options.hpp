// Options the user gave that nothing read: PETSc's -options_left, but on by default (main.cpp
// prints one warning per option after the run; -mlshell_options_left false silences it), with a
// "did you mean", and without the defaults mlshell sets itself (StepSolver's, which a chosen
// solver may not read). summary.json lists them as "unused_options".
//
// The user's options are those in the options database once the command line, PETSC_OPTIONS,
// the -options_file and the scene's solver.options_file are in (note_given_options); an option
// set later (mlshell's defaults) is never reported.
#pragma once

#include <string>
#include <vector>

namespace mlshell {

struct UnusedOption {
  std::string name;        ///< with its dash: -tao_rmtr_smoothr_qp
  std::string value;       ///< empty for a flag given without a value
  std::string suggestion;  ///< the closest known name, e.g. -tao_rmtr_smoother_qp; empty if none
  bool on_command_line = false;  ///< else from an options file or PETSC_OPTIONS
};

/// Notes the options in the database that nothing has read yet: the user's. Call once all of
/// them are in and before any component sets defaults; the same on every rank. `argv`: the
/// command line, whose options are reported also where no solver was built.
void note_given_options(int argc, char** argv);

/// The options noted by note_given_options() that nothing read since, in alphabetical order
/// (empty if it was never called). Without `solver_built` (-mlshell_evaluate,
/// -mlshell_material_csv: no step solver reads its options), only mlshell's own options and
/// those on the command line are reported, not the options files' solver configuration. A
/// suggestion is the known name (mlshell's options, and every option in the database that was
/// read or that mlshell set) nearest by edit distance, if at most a few edits away. Not
/// collective; the same on every rank.
std::vector<UnusedOption> unused_options(bool solver_built);

/// One line: "option -x (value v) was never used; did you mean -y?"
std::string describe(const UnusedOption& option);

/// Optimal string alignment distance: insertions, deletions, substitutions and swaps of two
/// neighbouring characters, each one edit.
std::size_t edit_distance(const std::string& a, const std::string& b);

}  // namespace mlshell
