#include "design_runs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <string_view>
#include <thread>

#include <fmt/format.h>

#include "child_runs.hpp"
#include "commands.hpp"
#include "core/error.hpp"
#include "human_format.hpp"
#include "io/json_path.hpp"
#include "scenario/content_hash.hpp"

namespace regodem::app {

using nlohmann::ordered_json;

namespace {

/// What an earlier study left in a run's directory.
struct Prior {
  bool done = false;
  std::string why;  // why it runs (again)
};

/// Done: summary.json says completed, for the same scenario bytes and --set list (the
/// scenario hash covers both). Files the scenario reads (a checkpoint, a particle file)
/// are not covered.
Prior prior_state(const fs::path& directory, const PlannedRun& run) {
  const fs::path summary_path = directory / "summary.json";
  std::error_code ignored;
  if (!fs::exists(summary_path, ignored))
    return {false, fs::exists(directory, ignored) ? "started before but did not finish" : ""};
  ordered_json summary;
  try {
    summary = ordered_json::parse(read_text(summary_path));
  } catch (const ordered_json::exception&) {
    return {false, "its summary.json cannot be read"};
  }
  // A summary of another shape (edited, or not a run's) is run again, saying why.
  const auto text_at = [&](const std::string& key) {
    const ordered_json& value = json_at_path(summary, key);
    if (!value.is_string()) throw InputError(fmt::format("'{}' is {}, not a text", key, value.dump()));
    return value.get<std::string>();
  };
  try {
    const std::string outcome = text_at("outcome");
    if (outcome != "completed") return {false, fmt::format("it ended '{}' before", outcome)};
    const std::string hash = scenario_content_hash(read_text(run.scenario), run.set);
    if (text_at("scenario.hash") != hash) return {false, "its inputs changed (the scenario file or the --set values)"};
  } catch (const InputError& problem) {
    return {false, fmt::format("{}: not a run's summary: {}", summary_path.string(), problem.what())};
  }
  return {true, ""};
}

/// The failed run's own message (summary.json), else the end of its log.
std::string failure_message(const fs::path& directory, const fs::path& log) {
  try {
    const ordered_json summary = read_summary(directory);
    const std::string message = summary.value("message", "");
    if (!message.empty()) return message;
  } catch (const std::exception&) {
  }
  std::string text = read_text(log);
  while (!text.empty() && text.back() == '\n') text.pop_back();
  const auto start = text.size() > 600 ? text.rfind('\n', text.size() - 600) : std::string::npos;
  return start == std::string::npos ? text : text.substr(start + 1);
}

}  // namespace

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string set_text(const std::string& path, double value, const std::string& unit) {
  return unit.empty() ? fmt::format("{}={}", path, value) : fmt::format("{}={} {}", path, value, unit);
}

std::string factor_set_text(const doe::CalibrationFactor& factor, double value) {
  if (factor.value_template.empty()) return set_text(factor.set_path, value, factor.design.unit);
  std::string text = factor.value_template;
  text.replace(text.find("{}"), 2, fmt::format("{}", value));  // the reader checked it holds one
  return factor.set_path + "=" + text;
}

std::string header(const std::string& name, const std::string& unit) {
  return unit.empty() ? name : fmt::format("{} [{}]", name, unit);
}

std::string runs_csv(const std::vector<doe::CalibrationFactor>& factors, const std::vector<NamedUnit>& responses,
                     const doe::CentralCompositeDesign& design, const std::vector<std::vector<double>>& y) {
  std::string text = "run,point_type";
  for (const auto& f : factors) text += "," + header(f.design.name, f.design.unit);
  for (const auto& r : responses) text += "," + header(r.name, r.unit);
  text += "\n";
  for (std::size_t p = 0; p < design.runs.size(); ++p) {
    text += fmt::format("point_{:02},{}", p + 1, doe::point_type_name(design.runs[p].type));
    for (const double v : design.runs[p].actual) text += fmt::format(",{}", v);
    for (const double v : y[p]) text += fmt::format(",{}", v);
    text += "\n";
  }
  return text;
}

std::vector<doe::FactorRange> design_ranges(const doe::CentralCompositeDesign& design) {
  std::vector<doe::FactorRange> ranges;
  for (std::size_t f = 0; f < design.factors.size(); ++f) {
    doe::FactorRange range{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    for (const auto& point : design.runs) {
      range.low = std::min(range.low, point.actual[f]);
      range.high = std::max(range.high, point.actual[f]);
    }
    ranges.push_back(range);
  }
  return ranges;
}

ordered_json read_summary(const fs::path& directory) {
  const fs::path file = directory / "summary.json";
  try {
    return ordered_json::parse(read_text(file));
  } catch (const ordered_json::exception& error) {
    throw InputError(fmt::format("{}: cannot be read as JSON: {}", file.string(), error.what()));
  }
}

double summary_number(const ordered_json& summary, const std::string& path, const std::string& where,
                      const std::string& run) {
  try {
    return json_number_at_path(summary, path);
  } catch (const InputError& problem) {
    throw InputError(fmt::format("{}: in runs/{}/summary.json: {}", where, run, problem.what()));
  }
}


RunLauncher RunLauncher::from(int ranks, const std::string& mpirun_command) {
  RunLauncher launcher;
  launcher.ranks = std::max(1, ranks);
  launcher.mpirun.clear();
  std::istringstream words(mpirun_command);
  for (std::string word; words >> word;) launcher.mpirun.push_back(word);
  if (launcher.ranks > 1 && launcher.mpirun.empty())
    throw InputError(
        "--mpirun is empty: runs over MPI ranks need a launcher that takes -np N (mpirun, mpiexec), or one whose "
        "words say where the count goes with {ranks} (srun -n {ranks})");
  return launcher;
}

std::vector<std::string> RunLauncher::launch_words() const {
  if (ranks <= 1) return {};
  static constexpr std::string_view placeholder = "{ranks}";
  const std::string count = std::to_string(ranks);
  std::vector<std::string> words;
  bool placed = false;
  for (std::string word : mpirun) {
    for (std::size_t at = word.find(placeholder); at != std::string::npos; at = word.find(placeholder, at)) {
      word.replace(at, placeholder.size(), count);
      at += count.size();
      placed = true;
    }
    words.push_back(std::move(word));
  }
  // mpirun and mpiexec take the count as -np N; a launcher that does not (srun) says where it goes.
  if (!placed) words.insert(words.end(), {"-np", count});
  return words;
}

std::string RunLauncher::description() const {
  if (ranks <= 1) return "";
  std::string command;
  for (const std::string& word : launch_words()) command += (command.empty() ? "" : " ") + word;
  return fmt::format(", over {} MPI ranks ({})", ranks, command);
}

int RunLauncher::processes(int option, int file, int threads_per_run) const {
  if (option > 0) return option;
  if (file > 0) return file;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()) / (threads_per_run * ranks));
}

RunBatches::RunBatches(fs::path output, int processes, int threads_per_run, RunLauncher launcher, int total_runs,
                       const std::atomic<int>& signals)
    : output_(std::move(output)),
      processes_(processes),
      threads_per_run_(threads_per_run),
      launcher_(std::move(launcher)),
      total_(total_runs),
      signals_(signals),
      program_(own_executable()) {}

void RunBatches::say(const std::string& line) {
  fmt::print("{}\n", line);
  std::fflush(stdout);  // progress must show when stdout is a file or a pipe
}

int RunBatches::run(const std::vector<PlannedRun>& runs) {
  std::vector<ChildJob> jobs;
  std::vector<const PlannedRun*> to_run;
  for (const PlannedRun& planned : runs) {
    const Prior prior = prior_state(directory(planned), planned);
    if (prior.done) {
      ++finished_;
      say(fmt::format("[{}/{}] {}: already done, skipped (runs/{}; {} of {} finished)", planned.number, total_,
                      planned.name, planned.name, finished_, total_));
      continue;
    }
    ChildJob job;
    if (launcher_.ranks > 1) {  // mpirun [its options] -np N (or where {ranks} says) regodem run ...
      const std::vector<std::string> words = launcher_.launch_words();
      job.arguments.assign(words.begin() + 1, words.end());
      job.arguments.push_back(program_);
    }
    job.arguments.insert(job.arguments.end(), {"run", planned.scenario, "-o", directory(planned).string(), "--threads",
                                               std::to_string(threads_per_run_)});
    for (const std::string& s : planned.set) {
      job.arguments.push_back("--set");
      job.arguments.push_back(s);
    }
    std::error_code ignored;
    if (fs::exists(directory(planned), ignored) && !fs::is_empty(directory(planned), ignored)) {
      job.arguments.push_back("--overwrite");
      say(fmt::format("{}: runs again: {}", planned.name, prior.why));
    }
    job.log = log(planned);
    jobs.push_back(std::move(job));
    to_run.push_back(&planned);
  }
  if (jobs.empty()) return exit_status::success;
  fs::create_directories(output_ / "logs");
  ChildEvents events;
  events.started = [&](std::size_t j) {
    say(fmt::format("[{}/{}] {} started{}", to_run[j]->number, total_, to_run[j]->name,
                    to_run[j]->description.empty() ? "" : ": " + to_run[j]->description));
  };
  events.finished = [&](std::size_t j, const ChildResult& result) {
    if (result.exit_code != 0) {
      say(fmt::format("[{}/{}] {} {} after {} (exit status {})", to_run[j]->number, total_, to_run[j]->name,
                      result.exit_code == exit_status::interrupted ? "stopped" : "FAILED",
                      format_wall_duration(result.wall_s), result.exit_code));
      return;
    }
    ++finished_;
    ++ran_;
    run_wall_s_ += result.wall_s;
    const int left = total_ - finished_;
    const double mean_s = run_wall_s_ / ran_;
    const double left_s = mean_s * std::ceil(static_cast<double>(left) / processes_);
    say(fmt::format("[{}/{}] {} done in {} ({} of {} finished){}", to_run[j]->number, total_, to_run[j]->name,
                    format_wall_duration(result.wall_s), finished_, total_,
                    left > 0
                        ? fmt::format("; about {} left ({} more, {} at once, {} a run on average)",
                                      format_wall_duration(left_s), left, processes_, format_wall_duration(mean_s))
                        : ""));
  };
  const auto results =
      run_children(launcher_.ranks > 1 ? launcher_.launch_words().front() : program_, jobs, processes_, signals_, events);
  if (signals_.load() > 0) return exit_status::interrupted;
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    if (results[j] && results[j]->exit_code != 0) {
      fmt::print(stderr, "regodem: error: run '{}' failed (exit status {}): {}\n  its outputs: {}\n  its log: {}\n",
                 to_run[j]->name, results[j]->exit_code, failure_message(directory(*to_run[j]), jobs[j].log),
                 directory(*to_run[j]).string(), jobs[j].log.string());
      return exit_status::run_failed;
    }
  }
  return exit_status::success;
}

doe::ResponseSurfaceFit fit_design_response(const std::vector<std::vector<double>>& x,
                                            const std::vector<double>& values,
                                            const std::vector<std::string>& factor_names, const std::string& terms,
                                            const std::string& name, const std::string& where) {
  const auto model_terms =
      terms.empty() ? doe::full_quadratic_terms(factor_names.size()) : doe::parse_terms(terms, factor_names);
  try {
    return doe::fit_response_surface(x, values, factor_names, model_terms, name);
  } catch (const InputError& problem) {
    throw InputError(fmt::format("{}: cannot fit: {}", where, problem.what()));
  }
}

}  // namespace regodem::app
