// The model checker under mutated model files. Every model in models/ (batch files aside: their
// check would run the cases) is mutated deterministically: misspelled and deleted keys, values of
// the wrong type, numbers replaced by 0, -1, huge, tiny, NaN, infinite and out-of-range integer
// values, files cut short, empty and binary files. `vorodec check` must exit 0 (with only
// warnings on stderr), or 2 with exactly one message on stderr, each within a few seconds:
// never a crash, a hang, an exit code 1 or a sanitizer report. One test per model, so ctest -j
// spreads them. VORODEC_FUZZ_MUTANTS=N samples N key and value mutants per model instead of 24
// (100000: all of them, about 2,700 in all); VORODEC_FUZZ_VERBOSE=1 prints every outcome.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace fs = std::filesystem;

namespace {

// Key and value mutants sampled per model; VORODEC_FUZZ_MUTANTS=N (e.g. 100000: all) for more.
std::size_t line_mutants() {
  const char* n = std::getenv("VORODEC_FUZZ_MUTANTS");
  return n ? static_cast<std::size_t>(std::strtoul(n, nullptr, 10)) : 24;
}
constexpr double kTimeout = 10.0;  // s, per `vorodec check` (sanitizer builds included)

struct Mutant {
  std::string name;  // what was changed, for failure messages
  std::string text;
};

struct Assignment {
  std::size_t line;
  std::string table;                   // the [table] or [[table]] header above it
  std::size_t key_begin, key_end;      // the key, in the line
  std::size_t value_begin, value_end;  // the value, in the line, without a trailing comment
};

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string join(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& l : lines) out += l + "\n";
  return out;
}

// `key = value  # comment` lines (keys bare or quoted), outside multi-line values.
std::vector<Assignment> assignments(const std::vector<std::string>& lines) {
  std::vector<Assignment> out;
  std::string table;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string& l = lines[i];
    const std::size_t first = l.find_first_not_of(" \t");
    if (first == std::string::npos || l[first] == '#') continue;
    if (l[first] == '[') {
      table = l.substr(first, l.rfind(']') + 1 - first);
      continue;
    }
    bool quoted = false;
    std::size_t eq = std::string::npos, comment = l.size();
    for (std::size_t k = first; k < l.size(); ++k) {
      if (l[k] == '"') quoted = !quoted;
      if (quoted) continue;
      if (l[k] == '=' && eq == std::string::npos) eq = k;
      if (l[k] == '#') {
        comment = k;
        break;
      }
    }
    if (eq == std::string::npos) continue;
    std::size_t key_end = eq;
    while (key_end > first && (l[key_end - 1] == ' ' || l[key_end - 1] == '\t')) --key_end;
    std::size_t value_begin = l.find_first_not_of(" \t", eq + 1);
    std::size_t value_end = comment;
    while (value_end > eq + 1 && (l[value_end - 1] == ' ' || l[value_end - 1] == '\t')) --value_end;
    if (value_begin == std::string::npos || value_begin >= value_end) continue;
    out.push_back({i, table, first, key_end, value_begin, value_end});
  }
  return out;
}

// Positions and lengths of the numbers in a value (not inside strings, not parts of names).
std::vector<std::pair<std::size_t, std::size_t>> numbers_in(const std::string& v) {
  std::vector<std::pair<std::size_t, std::size_t>> out;
  bool quoted = false;
  for (std::size_t k = 0; k < v.size(); ++k) {
    if (v[k] == '"') quoted = !quoted;
    if (quoted) continue;
    const bool starts = std::isdigit(static_cast<unsigned char>(v[k])) ||
                        ((v[k] == '-' || v[k] == '+') && k + 1 < v.size() &&
                         std::isdigit(static_cast<unsigned char>(v[k + 1])));
    const bool after_name = k > 0 && (std::isalnum(static_cast<unsigned char>(v[k - 1])) ||
                                      v[k - 1] == '_' || v[k - 1] == '.');
    if (!starts || after_name) continue;
    std::size_t e = k + 1;
    while (e < v.size() &&
           (std::isalnum(static_cast<unsigned char>(v[e])) || v[e] == '.' || v[e] == '_' ||
            ((v[e] == '-' || v[e] == '+') && (v[e - 1] == 'e' || v[e - 1] == 'E'))))
      ++e;
    out.push_back({k, e - k});
    k = e - 1;
  }
  return out;
}

std::uint64_t fnv1a(const std::string& s) {
  std::uint64_t h = 1469598103934665603ULL;
  for (const unsigned char c : s) h = (h ^ c) * 1099511628211ULL;
  return h;
}

// Deterministic mutants of one model file: all file-level mutants, every number of the
// [specimen] and [contact] tables made huge and tiny, and line_mutants() sampled (seeded by the
// file's name) from the misspelled, deleted, retyped and renumbered keys of the whole file.
std::vector<Mutant> mutants_of(const std::string& name, const std::string& text) {
  std::mt19937_64 random(fnv1a(name));
  const auto pick = [&random](std::size_t n) { return static_cast<std::size_t>(random() % n); };
  const std::vector<std::string> lines = split_lines(text);
  const std::vector<Assignment> keys = assignments(lines);
  std::vector<Mutant> out;

  for (const double f : {0.25, 0.5, 0.8}) {  // cut short, mid-line wherever it falls
    const auto at = static_cast<std::size_t>(f * static_cast<double>(text.size())) + pick(7);
    out.push_back({"truncated at byte " + std::to_string(at), text.substr(0, at)});
  }
  out.push_back({"empty file", ""});
  std::string garbage(700, '\0');
  for (char& c : garbage) c = static_cast<char>(random() & 0xff);
  out.push_back({"binary garbage", garbage});
  {
    std::string nul = text;
    nul.insert(pick(nul.size()), 1, '\0');
    out.push_back({"a NUL byte inside", nul});
  }

  const auto with_line = [&](std::size_t i, const std::string& line) {
    std::vector<std::string> copy = lines;
    copy[i] = line;
    return join(copy);
  };
  const auto replace_value = [&](const Assignment& a, const std::string& value) {
    const std::string& l = lines[a.line];
    return with_line(a.line, l.substr(0, a.value_begin) + value + l.substr(a.value_end));
  };
  const auto replace_number = [&](const Assignment& a, std::pair<std::size_t, std::size_t> num,
                                  const std::string& value) {
    const std::string& l = lines[a.line];
    const std::size_t at = a.value_begin + num.first;
    return with_line(a.line, l.substr(0, at) + value + l.substr(at + num.second));
  };
  const auto key_of = [&](const Assignment& a) {
    return a.table + " " + lines[a.line].substr(a.key_begin, a.key_end - a.key_begin);
  };

  // The lengths of the specimen and its contacts: every number huge and tiny.
  for (const Assignment& a : keys) {
    if (a.table != "[specimen]" && a.table != "[contact]") continue;
    const std::string value = lines[a.line].substr(a.value_begin, a.value_end - a.value_begin);
    for (const auto& num : numbers_in(value))
      for (const char* v : {"1e300", "1e-300"})
        out.push_back({key_of(a) + " = " + v, replace_number(a, num, v)});
  }

  // Key and value mutants by kind; sampled in turn from each kind, numbers twice as often.
  std::vector<std::vector<Mutant>> kinds(4);
  for (const Assignment& a : keys) {
    const std::string& l = lines[a.line];
    std::string key = l.substr(a.key_begin, a.key_end - a.key_begin);
    if (key.size() >= 3) {
      std::string typo = key;
      const std::size_t k = 1 + pick(typo.size() - 2);
      if (typo[k] != typo[k + 1] && typo[k + 1] != '"')
        std::swap(typo[k], typo[k + 1]);
      else
        typo.erase(k, 1);
      kinds[0].push_back(
          {key_of(a) + " misspelled " + typo,
           with_line(a.line, l.substr(0, a.key_begin) + typo + l.substr(a.key_end))});
    }
    kinds[1].push_back({key_of(a) + " deleted", with_line(a.line, "")});
    for (const char* v : {"\"text\"", "[1.0, 2.0]", "{ x = 1 }", "true", "1979-05-27"})
      kinds[2].push_back({key_of(a) + " = " + v, replace_value(a, v)});
    const std::string value = l.substr(a.value_begin, a.value_end - a.value_begin);
    for (const auto& num : numbers_in(value))
      for (const char* v : {"0", "-1", "-0.0", "1e300", "1e-300", "nan", "inf", "-inf",
                            "2147483648", "9223372036854775807", "-9223372036854775808"})
        kinds[3].push_back(
            {key_of(a) + " number " + value.substr(num.first, num.second) + " -> " + v,
             replace_number(a, num, v)});
  }
  for (std::size_t i = 0; i < lines.size(); ++i) {  // misspelled table names: [contatc]
    const std::string& l = lines[i];
    const std::size_t open = l.find_first_not_of("[ \t");
    if (l.empty() || l[0] != '[' || open == std::string::npos || l.size() < open + 3) continue;
    std::string typo = l;
    std::swap(typo[open], typo[open + 1]);
    if (typo != l) kinds[0].push_back({"table " + l + " misspelled " + typo, with_line(i, typo)});
  }
  for (auto& kind : kinds)  // Fisher-Yates by hand: std::shuffle is not the same everywhere
    for (std::size_t i = kind.size(); i > 1; --i) std::swap(kind[i - 1], kind[pick(i)]);
  const std::vector<std::size_t> turns{3, 0, 3, 1, 3, 2};
  std::vector<std::size_t> next(kinds.size(), 0);
  const std::size_t wanted = line_mutants();
  std::size_t total = 0;
  for (const auto& kind : kinds) total += kind.size();
  for (std::size_t t = 0, taken = 0; taken < std::min(wanted, total); ++t) {
    const std::size_t kind = turns[t % turns.size()];
    if (next[kind] >= kinds[kind].size()) continue;
    out.push_back(std::move(kinds[kind][next[kind]++]));
    ++taken;
  }
  return out;
}

struct Result {
  int code = -1;  // exit code; -1: killed by a signal (or by us, after the timeout)
  bool timed_out = false;
  double seconds = 0;
  std::string out, err;
};

std::string slurp(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// `vorodec check <model>`, stdout and stderr to files, killed after kTimeout seconds.
Result check(const fs::path& model, const fs::path& dir) {
  Result r;
  const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  std::string binary = VORODEC_BINARY, command = "check", file = model.string();
  char* argv[] = {binary.data(), command.data(), file.data(), nullptr};
  pid_t pid = 0;
  const auto start = std::chrono::steady_clock::now();
  const int spawned = posix_spawn(&pid, binary.c_str(), &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) {
    r.err = "posix_spawn failed";
    return r;
  }
  int status = 0;
  while (waitpid(pid, &status, WNOHANG) == 0) {
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (r.seconds > kTimeout) {
      r.timed_out = true;
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.code = !r.timed_out && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

// Exit 0 with only warnings on stderr, or exit 2 with one message naming a file of `dir` and a
// line: "error: <file>:<line>: ...".
::testing::AssertionResult acceptable(const Result& r, const fs::path& dir) {
  if (r.timed_out) return ::testing::AssertionFailure() << "no answer within " << kTimeout << " s";
  if (r.code != 0 && r.code != 2)
    return ::testing::AssertionFailure() << "exit code " << r.code << ", stderr:\n" << r.err;
  const std::vector<std::string> lines = split_lines(r.err);
  if (r.code == 0) {
    for (const std::string& l : lines)
      if (l.rfind("warning: ", 0) != 0)
        return ::testing::AssertionFailure() << "exit 0 with stderr line: " << l;
    if (r.out.find(": ok (") == std::string::npos)
      return ::testing::AssertionFailure() << "exit 0 without 'ok', stdout:\n" << r.out;
    return ::testing::AssertionSuccess();
  }
  if (lines.size() != 1 || r.err.back() != '\n')
    return ::testing::AssertionFailure()
           << "exit 2 with " << lines.size() << " stderr lines (one expected):\n"
           << r.err;
  const std::string& l = lines.front();
  if (l.rfind("error: " + dir.string() + "/", 0) != 0)
    return ::testing::AssertionFailure()
           << "exit 2, but the message is not 'error: <file>...': " << l;
  // The file is followed by its line, counted from 1.
  const std::size_t name_end = l.find(".toml:");
  const unsigned long line =
      name_end == std::string::npos ? 0 : std::strtoul(l.c_str() + name_end + 6, nullptr, 10);
  if (line < 1)
    return ::testing::AssertionFailure() << "exit 2, but the message gives no line >= 1: " << l;
  if (!r.out.empty()) return ::testing::AssertionFailure() << "exit 2 with stdout:\n" << r.out;
  return ::testing::AssertionSuccess();
}

std::vector<std::string> model_names() {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(fs::path(VORODEC_SOURCE_DIR) / "models")) {
    const std::string n = e.path().filename().string();
    if (e.path().extension() == ".toml" && n.rfind("batch_", 0) != 0) names.push_back(n);
  }
  std::sort(names.begin(), names.end());
  return names;
}

class ModelCheckerMutants : public ::testing::TestWithParam<std::string> {};

TEST_P(ModelCheckerMutants, Exit0Or2WithOneMessageWithinSeconds) {
  const fs::path models = fs::path(VORODEC_SOURCE_DIR) / "models";
  const std::string name = GetParam();
  // The mutant sits next to copies of every model, so that `base = "..."` finds the originals.
  const fs::path dir = fs::temp_directory_path() / ("vorodec_fuzz_" + std::to_string(getpid())) /
                       fs::path(name).stem();
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const auto& e : fs::directory_iterator(models))
    if (e.path().extension() == ".toml") fs::copy_file(e.path(), dir / e.path().filename());
  const std::vector<Mutant> list = mutants_of(name, slurp(models / name));
  ASSERT_GE(list.size(), 24u);
  const fs::path mutant = dir / ("mutant_" + name);
  int refused = 0, failures = 0;
  double slowest = 0;
  for (std::size_t i = 0; i < list.size(); ++i) {
    std::ofstream(mutant, std::ios::binary) << list[i].text;
    const Result r = check(mutant, dir);
    slowest = std::max(slowest, r.seconds);
    refused += r.code == 2;
    const ::testing::AssertionResult ok = acceptable(r, dir);
    if (std::getenv("VORODEC_FUZZ_VERBOSE"))
      std::printf("[%zu] %s: exit %d, %.2f s: %s", i, list[i].name.c_str(), r.code, r.seconds,
                  r.code == 2 ? r.err.c_str() : "\n");
    if (!ok) {
      const fs::path kept = dir / ("failed_" + std::to_string(i) + "_" + name);
      fs::copy_file(mutant, kept, fs::copy_options::overwrite_existing);
      ADD_FAILURE() << name << ", mutant " << i << " (" << list[i].name << ", kept as "
                    << kept.string() << "): " << ok.message();
      ++failures;
    }
  }
  std::printf("%s: %zu mutants, %d refused (exit 2), slowest check %.2f s\n", name.c_str(),
              list.size(), refused, slowest);
  if (failures == 0) fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(EveryModel, ModelCheckerMutants, ::testing::ValuesIn(model_names()),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                           return fs::path(param.param).stem().string();
                         });

}  // namespace
