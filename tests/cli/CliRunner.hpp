#pragma once
// Runs the umbra executable for tests and captures exit code, stdout and stderr.
#include <sys/wait.h>

#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace umbra::test {

struct RunResult {
  int exitCode = -1;
  std::string out, err;
};

inline std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

/// A profile CSV (`umbra profile shadow`: offset_km,r,g,b,luminance).
struct Csv {
  std::string header;
  std::vector<std::array<double, 5>> rows;
};

inline Csv readCsv(const std::string& path) {
  std::ifstream f(path);
  Csv c;
  std::getline(f, c.header);
  std::string line;
  while (std::getline(f, line)) {
    std::array<double, 5> row{};
    std::stringstream s(line);
    char comma;
    s >> row[0] >> comma >> row[1] >> comma >> row[2] >> comma >> row[3] >> comma >> row[4];
    c.rows.push_back(row);
  }
  return c;
}

inline std::string readAll(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

/// Runs `program args...` with the environment given (NAME=value) added.
inline RunResult run(const std::string& program, const std::vector<std::string>& args,
                     const std::vector<std::string>& env = {}) {
  const auto dir = std::filesystem::temp_directory_path();
  const std::string tag = std::to_string(::getpid()) + "-" + std::to_string(std::rand());
  const auto outPath = dir / ("umbra-test-out-" + tag), errPath = dir / ("umbra-test-err-" + tag);
  std::string cmd;
  for (const auto& e : env) cmd += e + " ";
  cmd += quote(program);
  for (const auto& a : args) cmd += " " + quote(a);
  cmd += " </dev/null >" + quote(outPath.string()) + " 2>" + quote(errPath.string());
  const int status = std::system(cmd.c_str());
  RunResult r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128;
  r.out = readAll(outPath);
  r.err = readAll(errPath);
  std::filesystem::remove(outPath);
  std::filesystem::remove(errPath);
  return r;
}

/// A fresh temporary directory, removed with its contents at the end of the scope.
struct TempDir {
  std::filesystem::path path;
  TempDir() {
    path = std::filesystem::temp_directory_path() /
           ("umbra-cli-test-" + std::to_string(::getpid()) + "-" + std::to_string(std::rand()));
    std::filesystem::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  std::string operator/(const std::string& name) const { return (path / name).string(); }
  /// Number of files in the directory (to check that nothing, not even a temporary, was left).
  int fileCount() const {
    int n = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(path)) ++n;
    return n;
  }
};

} // namespace umbra::test
