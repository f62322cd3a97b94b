// Options the user gave that nothing read (see unused_options.hpp).
#include "mlshell/unused_options.hpp"

#include <petscsys.h>

#include <algorithm>
#include <cctype>
#include <set>
#include <sstream>

namespace mlshell {

namespace {

/// Names (without the dash) that nothing had read when note_given_options() ran.
std::set<std::string>& given() {
  static std::set<std::string> names;
  return names;
}

/// Names (without the dash) on the command line.
std::set<std::string>& on_command_line() {
  static std::set<std::string> names;
  return names;
}

bool is_option_name(const char* word) {
  return word[0] == '-' && (std::isalpha(static_cast<unsigned char>(word[1])) || word[1] == '_');
}

/// mlshell's own options, so that a misspelt one is told the right name even where the user
/// did not give it (the option groups that read them: main.cpp, simulation.cpp,
/// step_solver.cpp).
constexpr const char* kMlshellOptions[] = {
    "-mlshell_scene_solver",   "-mlshell_output_dir",      "-mlshell_steps",
    "-mlshell_dt",             "-mlshell_refine",          "-mlshell_material_csv",
    "-mlshell_options_left",   "-mlshell_evaluate",        "-mlshell_quiet",
    "-mlshell_gauss_points",   "-mlshell_condition",       "-mlshell_condition_steps",
    "-mlshell_limit_csv",      "-mlshell_hierarchy_view",  "-mlshell_hierarchy_write",
    "-mlshell_step_solver",    "-mlshell_hessian_psd",     "-mlshell_force_rtol",
    "-mlshell_coarse_energy",  "-mlshell_pressure_psd",    "-mlshell_audit_intersections",
    "-mlshell_progressive_stop_level", "-mlshell_progressive_hessian",
    "-mlshell_progressive_gradient"};

/// PETSc's own options that only PetscFinalize reads, after mlshell's report.
constexpr const char* kReadByFinalize[] = {
    "-log_view",   "-log_view_memory", "-log_view_gpu_time", "-log_all", "-log_summary",
    "-log_mpe",    "-memory_view",     "-malloc_dump",       "-malloc_view",
    "-objects_dump", "-options_view",  "-options_left",      "-citations"};

/// Every option name in the database ("-name value -name -name value ..."), without dashes.
std::vector<std::string> names_in_database() {
  std::vector<std::string> names;
  char* all = nullptr;
  if (PetscOptionsGetAll(nullptr, &all) || !all) return names;
  std::istringstream words(all);
  PetscFree(all);
  std::string w;
  while (words >> w)
    if (is_option_name(w.c_str())) names.push_back(w.substr(1));
  return names;
}

}  // namespace

std::size_t edit_distance(const std::string& a, const std::string& b) {
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= n; ++i)
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[n][m];
}

void note_given_options(int argc, char** argv) {
  on_command_line().clear();
  for (int i = 1; i < argc; ++i)
    if (is_option_name(argv[i])) on_command_line().insert(argv[i] + 1);
  PetscInt n = 0;
  char **names = nullptr, **values = nullptr;
  if (PetscOptionsLeftGet(nullptr, &n, &names, &values)) return;
  given().clear();
  for (PetscInt i = 0; i < n; ++i) given().insert(names[i][0] == '-' ? names[i] + 1 : names[i]);
  PetscOptionsLeftRestore(nullptr, &n, &names, &values);
}

std::vector<UnusedOption> unused_options(bool solver_built) {
  std::vector<UnusedOption> unused;
  if (given().empty()) return unused;
  for (const char* name : kReadByFinalize) {
    PetscBool set;
    PetscOptionsHasName(nullptr, nullptr, name, &set);  // marks it read
  }
  PetscInt n = 0;
  char **names = nullptr, **values = nullptr;
  if (PetscOptionsLeftGet(nullptr, &n, &names, &values)) return unused;
  std::set<std::string> left;
  for (PetscInt i = 0; i < n; ++i) {
    const std::string name = names[i][0] == '-' ? names[i] + 1 : names[i];
    left.insert(name);
    const bool command_line = on_command_line().count(name) > 0;
    const bool reported = solver_built || command_line || name.starts_with("mlshell_");
    if (given().count(name) && reported)
      unused.push_back({"-" + name, values[i] ? values[i] : "", std::string(), command_line});
  }
  PetscOptionsLeftRestore(nullptr, &n, &names, &values);
  if (unused.empty()) return unused;
  // Known names: mlshell's, and every option in the database but the unused ones.
  std::set<std::string> known;
  for (const char* name : kMlshellOptions) known.insert(name + 1);
  for (const std::string& name : names_in_database())
    if (!left.count(name)) known.insert(name);
  for (UnusedOption& o : unused) {
    const std::string name = o.name.substr(1);
    const std::size_t within = std::max<std::size_t>(1, std::min<std::size_t>(3, name.size() / 4));
    std::size_t best = within + 1;
    for (const std::string& k : known) {
      const std::size_t d = edit_distance(name, k);
      if (d < best) best = d, o.suggestion = "-" + k;
    }
  }
  std::sort(unused.begin(), unused.end(),
            [](const UnusedOption& a, const UnusedOption& b) { return a.name < b.name; });
  return unused;
}

std::string describe(const UnusedOption& option) {
  std::string line = "option " + option.name;
  if (!option.value.empty()) line += " (value " + option.value + ")";
  line += " was never used";
  if (!option.suggestion.empty()) line += "; did you mean " + option.suggestion + "?";
  return line;
}

}  // namespace mlshell
