// Frame-parallel stereo_sim runs (sm_sim_shards.hpp).
#include "sm_sim_shards.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>

#include "sm_sim_outputs.hpp"
#include "sm_sim_report.hpp"
#include "toolio/sm_cli.hpp"
#include "toolio/sm_io.hpp"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace sm::simapp {

void add_shard_options(CLI::App& app, ShardOptions& o) {
  app.add_option("--jobs", o.jobs,
                 "simulate the frames in N contiguous shards, each in its own process from reset, and merge them "
                 "(per-frame results as a serial run; timing figures from the first shard)")
      ->check(tools::int_in(1, 256))
      ->capture_default_str();
  app.add_option("--frame-range", o.range,
                 "A:B: simulate frames A..B-1 of the run only (a shard), from reset with the registers in force at "
                 "frame A; B empty: to the last frame");
  app.add_option("--list-shards", o.list_shards,
                 "print the frame ranges (A:B) of N shards of this run, one a line, after checking its inputs and "
                 "registers, and exit (for tools/sm_farm.py)")
      ->check(tools::int_in(1, 100000));
  app.add_option("--merge-shards", o.merge, "merge these shard folders (--frame-range runs of one input) into --out")
      ->expected(1, -1);
}

namespace {

std::optional<int> shard_error(const std::string& msg) {
  fmt::print(stderr, "stereo_sim: error: {}\n", msg);
  return 2;
}

bool parse_range(const std::string& s, size_t& a, size_t& b) {
  const size_t colon = s.find(':');
  if (colon == std::string::npos || colon == 0) return false;
  try {
    size_t used = 0;
    const long long av = std::stoll(s.substr(0, colon), &used);
    if (used != colon || av < 0) return false;
    a = static_cast<size_t>(av);
    b = 0;
    if (colon + 1 == s.size()) return true;
    const long long bv = std::stoll(s.substr(colon + 1), &used);
    if (used != s.size() - colon - 1 || bv <= av) return false;
    b = static_cast<size_t>(bv);
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace

std::optional<int> check_shard_options(SimOptions& opt) {
  ShardOptions& s = opt.shard;
  s.given = !s.range.empty();
  if (s.given && !parse_range(s.range, s.first, s.end))
    return shard_error(fmt::format("--frame-range {}: expected A:B with 0 <= A < B (or A: to the end)", s.range));
  const bool parallel = s.jobs > 1 || s.given || !s.merge.empty();
  if ((s.jobs > 1) + s.given + !s.merge.empty() + (s.list_shards > 0) > 1)
    return shard_error("--jobs, --frame-range, --list-shards and --merge-shards exclude each other");
  if (parallel && (!opt.wave_path.empty() || opt.wave_list_scopes || !opt.wave_list.empty()))
    return shard_error("--wave, --wave-scopes and --wave-list need a whole run (no --jobs, --frame-range)");
  if (parallel && opt.depth.any())
    return shard_error("--depth-file, --cloud and --cloud-view need a whole run (no --jobs, --frame-range)");
  if (s.given && fs::path(opt.disp_file).parent_path().lexically_normal() != fs::path(opt.out_dir).lexically_normal())
    return shard_error(fmt::format("--disp-file {}: a shard (--frame-range) writes its disparity into --out {}",
                                   opt.disp_file, opt.out_dir));
  return std::nullopt;
}

void start_shard(const SimOptions& opt, const HwConfig& hw, RegisterPlan& plan, SimInput& in) {
  const size_t n = in.nframes;
  const size_t first = opt.shard.first, end = opt.shard.end ? opt.shard.end : n;
  if (first >= n || end > n)
    fail(fmt::format("--frame-range {}: the run has {} frame(s) ({})", opt.shard.range, n, in.source->note()));
  // The host's schedule of the whole run says what changed for each frame (the report);
  // the shard's own schedule starts from frame `first`'s registers written at reset.
  const HostSchedule whole = schedule_host_writes(plan, hw, opt.late_regs);
  plan.host_report.assign(whole.frames.begin() + static_cast<long>(first),
                          whole.frames.begin() + static_cast<long>(end));
  plan.regs =
      std::vector<Regs>(plan.regs.begin() + static_cast<long>(first), plan.regs.begin() + static_cast<long>(end));
  plan.first = first;
  in.first = first;
  in.nframes = end - first;
  in.source->skip(first);
}

namespace {

// The options a shard sets for itself: each is followed by its value.
const std::vector<std::string> kShardOwn = {"--jobs", "--out", "--disp-file", "--frame-range"};

// The run's command line without the program, -q and the options a shard sets for itself:
// the same for every shard of one run.
std::vector<std::string> run_args(const std::vector<std::string>& argv) {
  std::vector<std::string> a;
  for (size_t i = 1; i < argv.size(); ++i) {
    const std::string& t = argv[i];
    if (t == "-q" || t == "--quiet") continue;
    if (std::find(kShardOwn.begin(), kShardOwn.end(), t) != kShardOwn.end()) {
      ++i;
      continue;
    }
    if (std::none_of(kShardOwn.begin(), kShardOwn.end(),
                     [&](const std::string& d) { return t.rfind(d + "=", 0) == 0; }))
      a.push_back(t);
  }
  return a;
}

}  // namespace

void add_shard_info(const SimOptions& opt, const SimInput& in, const std::vector<std::string>& status_lines,
                    json& rep) {
  rep["shard"] = {{"run", run_args(opt.shard.argv)},
                  {"status_lines", status_lines},
                  {"first", in.first},
                  {"count", in.nframes},
                  {"total", in.total},
                  {"disparity_name", fs::path(opt.disp_file).filename().string()},
                  {"disparity_each_frame", opt.disp_each},
                  {"core_mhz_given", opt.core_mhz_given}};
}

namespace {

// ---- --jobs: the shards' processes ----

struct Shard {
  size_t first = 0, end = 0;
  std::string dir, log;
  pid_t pid = -1;
};

std::vector<Shard> split(size_t nframes, int jobs, const std::string& tmp) {
  const size_t k = std::min<size_t>(static_cast<size_t>(jobs), nframes);
  std::vector<Shard> s(k);
  size_t f = 0;
  for (size_t i = 0; i < k; ++i) {
    s[i].first = f;
    f += nframes / k + (i < nframes % k ? 1 : 0);
    s[i].end = f;
    s[i].dir = fmt::format("{}/shard_{:03d}", tmp, i);
    s[i].log = s[i].dir + ".log";
  }
  return s;
}

// The command line of a shard: this run's, less --jobs, --out, --disp-file and -q.
std::vector<std::string> shard_args(const SimOptions& opt, const Shard& s) {
  std::vector<std::string> a = run_args(opt.shard.argv);
  const std::string ext = fs::path(opt.disp_file).extension().string();
  for (const std::string& t : {std::string("--frame-range"), fmt::format("{}:{}", s.first, s.end), std::string("--out"),
                               s.dir, std::string("--disp-file"), s.dir + "/disparity" + ext, std::string("-q")})
    a.push_back(t);
  return a;
}

pid_t spawn(const std::string& exe, const std::vector<std::string>& args, const std::string& log) {
  std::vector<char*> argv;
  std::string argv0 = exe;
  argv.push_back(argv0.data());
  std::vector<std::string> copy = args;
  for (auto& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid < 0) fail("cannot start a shard's process (fork)");
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      dup2(fd, 1);
      dup2(fd, 2);
    }
    execv(exe.c_str(), argv.data());
    _exit(127);
  }
  return pid;
}

std::string last_line(const std::string& path) {
  std::ifstream f(path);
  std::string line, last;
  while (std::getline(f, line))
    if (!line.empty()) last = line.substr(line.rfind('\r') == std::string::npos ? 0 : line.rfind('\r') + 1);
  return last.empty() ? "no output" : last;
}

// A shard succeeded when it exited 0 (bit-exact), 1 (a mismatch, reported) or 3 (the
// --core-mhz budget verdict NO, reported) with its report.
bool shard_ok(int status, const Shard& s) {
  return WIFEXITED(status) && (WEXITSTATUS(status) <= 1 || WEXITSTATUS(status) == 3) &&
         fs::exists(s.dir + "/report.json");
}

std::string exit_text(int status) {
  return WIFEXITED(status) ? fmt::format("exit {}", WEXITSTATUS(status))
                           : fmt::format("signal {}", WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

// Waits for every shard; the first failure stops the others.
void wait_shards(std::vector<Shard>& shards, bool quiet) {
  const auto t0 = std::chrono::steady_clock::now();
  std::string error;
  for (size_t done = 0; done < shards.size(); ++done) {
    int status = 0;
    const pid_t pid = waitpid(-1, &status, 0);
    auto it = std::find_if(shards.begin(), shards.end(), [&](const Shard& s) { return s.pid == pid; });
    if (it == shards.end()) {
      --done;
      continue;
    }
    it->pid = -1;
    if (!shard_ok(status, *it) && error.empty()) {
      error = fmt::format("shard {} (frames {}..{}) failed ({}): {}", it - shards.begin(), it->first, it->end - 1,
                          exit_text(status), last_line(it->log));
      for (const Shard& s : shards)
        if (s.pid > 0) kill(s.pid, SIGTERM);
    }
    if (!quiet) {
      const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const size_t n = done + 1;
      fmt::print(stderr, "\rshards done {}/{} ({:.1f} s, about {:.0f} s left)", n, shards.size(), el,
                 el / static_cast<double>(n) * static_cast<double>(shards.size() - n));
      if (n == shards.size()) fmt::print(stderr, "\n");
    }
  }
  if (!error.empty()) fail(error);
}

// Removes the shards' folder however run_jobs ends.
struct TmpDir {
  std::string path;
  ~TmpDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

}  // namespace

std::vector<std::string> shard_ranges(size_t nframes, int shards) {
  std::vector<std::string> r;
  for (const Shard& s : split(nframes, shards, "")) r.push_back(fmt::format("{}:{}", s.first, s.end));
  return r;
}

int run_jobs(const SimOptions& opt, size_t nframes) {
  const auto t0 = std::chrono::steady_clock::now();
  const fs::path out = fs::path(opt.out_dir).lexically_normal();
  const fs::path parent = out.parent_path().empty() ? fs::path(".") : out.parent_path();
  fs::create_directories(parent);
  TmpDir tmp{(parent / fmt::format(".{}.jobs{}", out.filename().string(), ::getpid())).string()};
  fs::create_directories(tmp.path);
  std::vector<Shard> shards = split(nframes, opt.shard.jobs, tmp.path);
  const std::string exe = fs::read_symlink("/proc/self/exe").string();
  if (!opt.quiet) fmt::print(stderr, "stereo_sim: {} frames in {} shards, one process each\n", nframes, shards.size());
  for (Shard& s : shards) s.pid = spawn(exe, shard_args(opt, s), s.log);
  wait_shards(shards, opt.quiet);
  std::vector<std::string> dirs;
  for (const Shard& s : shards) dirs.push_back(s.dir);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return merge_shards(dirs, opt.out_dir, opt.disp_file, opt.quiet, wall);
}

namespace {

// ---- the merge ----

struct ShardReport {
  std::string dir;
  json rep;
  size_t first = 0, count = 0, total = 0;
};

json read_json(const std::string& path) {
  std::ifstream f(path);
  if (!f) fail(fmt::format("{}: cannot read (not a shard folder?)", path));
  json j = json::parse(f, nullptr, false);
  if (j.is_discarded() || !j.is_object()) fail(fmt::format("{}: not a JSON report", path));
  return j;
}

// The shards, in frame order; they must cover one run's frames exactly once.
std::vector<ShardReport> read_shards(const std::vector<std::string>& dirs) {
  std::vector<ShardReport> v;
  for (const auto& d : dirs) {
    const std::string path = d + "/report.json";
    ShardReport s{d, read_json(path)};
    if (!s.rep.contains("shard") || !s.rep.contains("frame_results"))
      fail(fmt::format("{}: not a shard's report (run with --frame-range)", path));
    try {
      s.first = s.rep["shard"].at("first").get<size_t>();
      s.count = s.rep["shard"].at("count").get<size_t>();
      s.total = s.rep["shard"].at("total").get<size_t>();
    } catch (const json::exception& e) {
      fail(fmt::format("{}: 'shard': {}", path, e.what()));
    }
    v.push_back(std::move(s));
  }
  for (const auto& s : v) {
    if (!s.rep["shard"].contains("run"))
      fail(fmt::format("{}/report.json: no 'shard.run' (a shard of an older stereo_sim: run it again)", s.dir));
    if (s.rep["shard"]["run"] != v.front().rep["shard"]["run"])
      fail(
          fmt::format("{}: a shard of another run (its command line, less the shard's own options, differs from "
                      "{}'s)",
                      s.dir, v.front().dir));
  }
  std::sort(v.begin(), v.end(), [](const ShardReport& a, const ShardReport& b) { return a.first < b.first; });
  size_t next = 0;
  for (const auto& s : v) {
    if (s.first != next || s.total != v.front().total)
      fail(fmt::format("{}: frames {}..{} of {}, but the next frame of the run is {} of {}", s.dir, s.first,
                       s.first + s.count - 1, s.total, next, v.front().total));
    next += s.count;
  }
  if (next != v.front().total)
    fail(fmt::format("the shards hold frames 0..{} of a run of {} frames", next - 1, v.front().total));
  return v;
}

// Files to copy into the merged output: (from, to).
using Copies = std::vector<std::pair<std::string, std::string>>;

Copies output_files(const std::vector<ShardReport>& v, const std::string& out_dir, const std::string& disp_file) {
  Copies c;
  const ShardReport& last = v.back();
  const std::string name = last.rep["shard"].value("disparity_name", "disparity.pfm");
  c.emplace_back(last.dir + "/" + name, disp_file);
  for (const char* pic : {"disparity.png", "disparity_color.png", "panel.png"})
    if (fs::exists(last.dir + "/" + pic)) c.emplace_back(last.dir + "/" + pic, out_dir + "/" + pic);
  for (const auto& s : v) {
    if (!s.rep["shard"].value("disparity_each_frame", false)) continue;
    const std::string sd = s.dir + "/" + s.rep["shard"].value("disparity_name", "disparity.pfm");
    for (size_t f = s.first; f < s.first + s.count; ++f)
      c.emplace_back(frame_disparity_path(sd, f), frame_disparity_path(disp_file, f));
  }
  for (const auto& [from, to] : c)
    if (!fs::exists(from)) fail(fmt::format("{}: missing (an incomplete shard)", from));
  return c;
}

// The shards' checks: per-frame results in order, mismatches summed, the first one's
// description, framing and bit-exactness over all.
void merge_checks(const std::vector<ShardReport>& v, json& m) {
  json frames = json::array();
  int mismatches = 0;
  bool framing = true, checked = true, exact = true;
  m.erase("first_mismatch");
  m.erase("framing_error");
  for (const auto& s : v) {
    const json& r = s.rep;
    for (const auto& fr : r["frame_results"]) frames.push_back(fr);
    mismatches += r.value("mismatches", 0);
    if (r.contains("first_mismatch") && !m.contains("first_mismatch")) m["first_mismatch"] = r["first_mismatch"];
    if (!r.value("framing_ok", true) && framing) m["framing_error"] = r.value("framing_error", "");
    framing = framing && r.value("framing_ok", true);
    checked = checked && !r["bit_exact"].is_null();
    exact = exact && r["bit_exact"].is_boolean() && r["bit_exact"].get<bool>();
  }
  m["frame_results"] = frames;
  m["mismatches"] = mismatches;
  m["bit_exact"] = checked ? json(exact && mismatches == 0) : json(nullptr);
  m["framing_ok"] = framing;
}

// The register schedule: the writes of the shards' schedules, their errors.
void merge_schedule(const std::vector<ShardReport>& v, json& m) {
  json errors = json::array();
  uint64_t writes = 0;
  bool ok = true;
  for (const auto& s : v) {
    const json& rs = s.rep["register_schedule"];
    writes += rs.value("axi_writes", uint64_t{0});
    ok = ok && rs.value("ok", true);
    if (rs.contains("errors"))
      for (const auto& e : rs["errors"]) errors.push_back(e);
  }
  json& ms = m["register_schedule"];
  ms["axi_writes"] = writes;
  ms["ok"] = ok;
  ms.erase("errors");
  if (!errors.empty()) ms["errors"] = errors;
}

// The shards' simulation times; `wall` > 0: the whole run's, else the longest shard's.
void merge_speed(const std::vector<ShardReport>& v, double wall, json& m) {
  json shards = json::array();
  double cycles = 0, max_wall = 0;
  for (const auto& s : v) {
    const double w = s.rep.value("sim_wall_seconds", 0.0);
    cycles += s.rep.value("sim_cycles_per_second", 0.0) * w;
    max_wall = std::max(max_wall, w);
    shards.push_back({{"first", s.first}, {"count", s.count}, {"sim_wall_seconds", w}, {"folder", s.dir}});
  }
  m["shards"] = shards;
  wall = wall > 0 ? wall : max_wall;
  m["sim_wall_seconds"] = wall;
  m["sim_frames_per_second"] = static_cast<double>(v.front().total) / wall;
  m["sim_cycles_per_second"] = cycles / wall;
}

// The whole run's report: shard 0's (its timing figures: frames streamed back to back),
// every shard's per-frame results and checks, the last shard's status and accuracy.
json merge_reports(const std::vector<ShardReport>& v, const std::string& disp_file, double wall) {
  json m = v.front().rep;
  m.erase("shard");
  m["frames"] = v.front().total;
  merge_checks(v, m);
  merge_schedule(v, m);
  const json& last = v.back().rep;
  m["status"] = last["status"];
  m["status_note"] = fmt::format(
      "read back after the last shard, which ran frames {}..{} from its own reset: counters such as "
      "STATUS.FRAME_COUNT count those {} frames, not the run's {}",
      v.back().first, v.back().first + v.back().count - 1, v.back().count, v.front().total);
  for (const char* k : {"bad1_percent", "ground_truth", "invalid"}) {
    m.erase(k);
    if (last.contains(k)) m[k] = last[k];
  }
  const size_t n0 = v.front().count;
  m["timing_frames"] = {{"first", 0},
                        {"count", n0},
                        {"note", fmt::format("the timing figures are those of frames 0..{}, streamed back to back in "
                                             "the first of {} shards; the status is read back after the last",
                                             n0 - 1, v.size())}};
  merge_speed(v, wall, m);
  std::string starts;
  for (const auto& s : v) starts += (starts.empty() ? "" : ", ") + std::to_string(s.first);
  m["frame_cycles_note"] = fmt::format(
      "frame_results' cycles are counted from each shard's own reset (shards from frames {}), after the register "
      "writes of that reset, so they differ from a serial run's by a few cycles or by whole frames; the intervals "
      "within a frame (latency, sof to last pixel out) do not",
      starts);
  m["disparity_file"] = disp_file;
  return m;
}

void print_merged(const json& m, const json& status_lines, const std::string& out_dir) {
  const json& c = m["config"];
  fmt::print("stereo_sim: {} frame(s) of {}x{}, DISP {}, census {}x{}, SW {}x{}, in {} shards\n",
             m["frames"].get<size_t>(), c.value("width", 0), c.value("height", 0), c.value("disp", 0),
             c.value("census", 0), c.value("census", 0), c.value("sw", 0), c.value("sw", 0), m["shards"].size());
  fmt::print("  input: {}\n", m.value("frames_note", m.value("input", "")));
  fmt::print("  timing ({}):\n", m["timing_frames"]["note"].get<std::string>());
  fmt::print("    cycles per frame (sof in -> last pixel out): {}; steady-state frame period: {} cycles\n",
             m.value("cycles_per_frame_sof_to_last_pixel", 0), m.value("steady_state_frame_period_cycles", 0));
  fmt::print("    latency (sof in -> first pixel out): {} cycles; input stalls: {} cycles\n",
             m.value("latency_cycles", 0), m.value("input_stall_cycles", 0));
  fmt::print("    30 frames/s with this camera at this core clock: {}\n",
             m.value("meets_30fps_with_camera_at_core_clock", false) ? "yes" : "NO");
  fmt::print("  framing: {}\n", m["framing_ok"].get<bool>() ? "ok" : m.value("framing_error", "error"));
  if (!m["bit_exact"].is_null())
    fmt::print("  bit-exact vs model: {}\n",
               m["bit_exact"].get<bool>() ? std::string("yes")
                                          : fmt::format("NO, {} mismatches, first: {}", m["mismatches"].get<int>(),
                                                        m.value("first_mismatch", "")));
  const json& rs = m["register_schedule"];
  if (!rs["files"].empty())
    fmt::print("  register schedule: {} file(s), {} AXI4-Lite writes while streaming{}\n", rs["files"].size(),
               rs["axi_writes"].get<uint64_t>(),
               rs.contains("errors") ? "; " + rs["errors"][0].get<std::string>() : "");
  print_objects(m["frame_results"]);
  fmt::print("  status read back over AXI4-Lite ({}):\n", m["status_note"].get<std::string>());
  for (const auto& l : status_lines) fmt::print("    {}\n", l.get<std::string>());
  if (m.contains("invalid")) fmt::print("  last frame: {}\n", invalid_line(m["invalid"]));
  if (m.contains("bad1_percent"))
    fmt::print("  bad-1.0 vs ground truth (last frame): {:.2f} %\n", m["bad1_percent"].get<double>());
  fmt::print("  simulation: {:.2f} s wall, {:.2f} frames/s\n", m["sim_wall_seconds"].get<double>(),
             m["sim_frames_per_second"].get<double>());
  fmt::print("  outputs in {}/ (lossless disparity: {})\n", out_dir, m["disparity_file"].get<std::string>());
}

}  // namespace

int merge_shards(const std::vector<std::string>& dirs, const std::string& out_dir, std::string disp_file, bool quiet,
                 double wall) {
  const std::vector<ShardReport> v = read_shards(dirs);
  const fs::path out_abs = fs::weakly_canonical(fs::absolute(out_dir));
  for (const auto& s : v)
    if (fs::weakly_canonical(fs::absolute(s.dir)) == out_abs)
      fail(fmt::format("--out {}: one of the shard folders being merged", out_dir));
  if (disp_file.empty())
    disp_file = out_dir + "/" + v.back().rep["shard"].value("disparity_name", std::string("disparity.pfm"));
  const Copies copies = output_files(v, out_dir, disp_file);
  const json m = merge_reports(v, disp_file, wall);
  // Every input checked: now the files, each under a temporary name renamed when
  // complete, report.json last.
  fs::create_directories(out_dir);
  for (const auto& [from, to] : copies) {
    const fs::path dir = fs::path(to).parent_path();
    if (!dir.empty()) fs::create_directories(dir);
    const std::string part = fmt::format("{}.part{}", to, ::getpid());
    fs::copy_file(from, part, fs::copy_options::overwrite_existing);
    fs::rename(part, to);
  }
  tools::write_json_atomic(out_dir + "/report.json", m);
  (void)quiet;
  print_merged(m, v.back().rep["shard"].value("status_lines", json::array()), out_dir);
  const bool ok = (m["bit_exact"].is_null() || m["bit_exact"].get<bool>()) && m["framing_ok"].get<bool>() &&
                  m["register_schedule"]["ok"].get<bool>();
  // as a serial run: 3 when --core-mhz was given and the 30 frames/s verdict is NO
  const bool budget_no =
      v.front().rep["shard"].value("core_mhz_given", false) && !m.value("meets_30fps_with_camera_at_core_clock", true);
  return !ok ? 1 : budget_no ? 3 : 0;
}

int merge_shard_dirs(const std::vector<std::string>& dirs, const std::string& out_dir, bool quiet) {
  return merge_shards(dirs, out_dir, "", quiet);
}

}  // namespace sm::simapp
