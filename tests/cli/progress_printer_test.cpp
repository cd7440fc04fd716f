// glint-render's progress output (apps/progress_printer.hpp): format_seconds, and
// ProgressPrinter fed fixed sequences of progress reports, its stderr redirected to a file (a log:
// a line per tenth of the work) or to a pseudo-terminal (one line redrawn in place). The expected
// text is worked out by hand from the reports: ETA = elapsed * (1 - fraction) / fraction, with
// elapsed times chosen so that every number printed is exact.

#include "progress_printer.hpp"
#include "load_progress.hpp"

#include <catch2/catch.hpp>

#include <fcntl.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <cstdio>
#include <string>
#include <vector>

namespace {

using glint::cli::format_seconds;
using glint::cli::ProgressPrinter;

/// Runs `write` with file descriptor 2 (stderr) pointing at `target`, then puts it back.
template <typename Write>
void with_stderr_on(int target, Write&& write) {
  std::fflush(stderr);
  const int saved = dup(2);
  REQUIRE(saved >= 0);
  REQUIRE(dup2(target, 2) == 2);
  write();
  std::fflush(stderr);
  dup2(saved, 2);
  close(saved);
}

/// What ProgressPrinter(enabled) prints for `reports` when stderr is a file.
std::string printed_to_file(bool enabled, const std::vector<glint::RenderProgress>& reports) {
  std::FILE* file = std::tmpfile();
  REQUIRE(file != nullptr);
  with_stderr_on(fileno(file), [&] {
    ProgressPrinter printer(enabled);
    for (const glint::RenderProgress& p : reports)
      printer(p);
  });
  std::string text;
  std::rewind(file);
  for (int c = std::fgetc(file); c != EOF; c = std::fgetc(file))
    text += char(c);
  std::fclose(file);
  return text;
}

/// A report of `done` of `total` units of work (the last call when all is done).
glint::RenderProgress report(int done, int total, double elapsed) {
  glint::RenderProgress p;
  p.samples_done = std::uint64_t(done);
  p.samples_total = std::uint64_t(total);
  p.elapsed_seconds = elapsed;
  p.last = done == total;
  return p;
}

/// Reports of a render of 16 tiles taking half a second per tile, for the given tile counts.
std::vector<glint::RenderProgress> sixteenths(const std::vector<int>& done) {
  std::vector<glint::RenderProgress> reports;
  for (const int k : done)
    reports.push_back(report(k, 16, 0.5 * k));
  return reports;
}

}  // namespace

TEST_CASE("format_seconds: tenths under a minute, then minutes, then hours", "[cli][progress]") {
  CHECK(format_seconds(0.0) == "0.0 s");
  CHECK(format_seconds(2.5) == "2.5 s");
  CHECK(format_seconds(59.94) == "59.9 s");
  CHECK(format_seconds(60.0) == "1m00s");
  CHECK(format_seconds(61.9) == "1m01s");
  CHECK(format_seconds(3599.0) == "59m59s");
  CHECK(format_seconds(3600.0) == "1h00m");
  CHECK(format_seconds(90061.0) == "25h01m");
}

TEST_CASE("in a log, progress is a line per tenth of the work, ending at 100%", "[cli][progress]") {
  SECTION("a report after every tile: one line per tenth, the first of each") {
    std::vector<int> every;
    for (int k = 1; k <= 16; ++k)
      every.push_back(k);
    CHECK(printed_to_file(true, sixteenths(every)) ==
          "[  6%] 0.5 s elapsed, ETA 7.5 s   \n"
          "[ 12%] 1.0 s elapsed, ETA 7.0 s   \n"
          "[ 25%] 2.0 s elapsed, ETA 6.0 s   \n"
          "[ 31%] 2.5 s elapsed, ETA 5.5 s   \n"
          "[ 43%] 3.5 s elapsed, ETA 4.5 s   \n"
          "[ 50%] 4.0 s elapsed, ETA 4.0 s   \n"
          "[ 62%] 5.0 s elapsed, ETA 3.0 s   \n"
          "[ 75%] 6.0 s elapsed, ETA 2.0 s   \n"
          "[ 81%] 6.5 s elapsed, ETA 1.5 s   \n"
          "[ 93%] 7.5 s elapsed, ETA 0.5 s   \n"
          "[100%] 8.0 s elapsed, ETA 0.0 s   \n");
  }
  SECTION("reports that skip tiles, as when the caller wakes late") {
    CHECK(printed_to_file(true, sixteenths({3, 9, 16})) ==
          "[ 18%] 1.5 s elapsed, ETA 6.5 s   \n"
          "[ 56%] 4.5 s elapsed, ETA 3.5 s   \n"
          "[100%] 8.0 s elapsed, ETA 0.0 s   \n");
  }
  SECTION("the last report alone") {
    CHECK(printed_to_file(true, sixteenths({16})) == "[100%] 8.0 s elapsed, ETA 0.0 s   \n");
  }
  SECTION("nothing done yet: no estimate") {
    CHECK(printed_to_file(true, {report(0, 16, 0.0)}) == "[  0%] 0.0 s elapsed, ETA --   \n");
  }
  SECTION("long renders: minutes and hours") {
    CHECK(printed_to_file(true, {report(1, 4, 30.0), report(2, 4, 75.0), report(3, 4, 5400.0),
                                 report(4, 4, 7200.0)}) ==
          "[ 25%] 30.0 s elapsed, ETA 1m30s   \n"
          "[ 50%] 1m15s elapsed, ETA 1m15s   \n"
          "[ 75%] 1h30m elapsed, ETA 30m00s   \n"
          "[100%] 2h00m elapsed, ETA 0.0 s   \n");
  }
  SECTION("a stopped render: its last report is printed, whatever its tenth") {
    glint::RenderProgress stopped = report(6, 16, 3.0);
    stopped.last = true;
    CHECK(printed_to_file(true, {report(5, 16, 2.5), stopped}) ==
          "[ 31%] 2.5 s elapsed, ETA 5.5 s   \n"
          "[ 37%] 3.0 s elapsed, ETA 5.0 s   \n");
  }
  SECTION("a resumed render: the share done counts its saved samples, the ETA this run's speed") {
    std::vector<glint::RenderProgress> reports{report(8, 16, 0.0), report(10, 16, 1.0),
                                               report(16, 16, 4.0)};
    for (glint::RenderProgress& p : reports)
      p.samples_at_start = 8;
    CHECK(printed_to_file(true, reports) ==
          "[ 50%] 0.0 s elapsed, ETA --   \n"
          "[ 62%] 1.0 s elapsed, ETA 3.0 s   \n"
          "[100%] 4.0 s elapsed, ETA 0.0 s   \n");
  }
  SECTION("--quiet: nothing") {
    CHECK(printed_to_file(false, sixteenths({1, 2, 8, 16})).empty());
  }
}

TEST_CASE("on a terminal, progress is one line redrawn at most every 0.1 s", "[cli][progress]") {
  int master = -1, slave = -1;
  REQUIRE(openpty(&master, &slave, nullptr, nullptr, nullptr) == 0);
  termios raw{};
  REQUIRE(tcgetattr(slave, &raw) == 0);
  cfmakeraw(&raw);  // no newline translation: read back exactly what was written
  REQUIRE(tcsetattr(slave, TCSANOW, &raw) == 0);
  with_stderr_on(slave, [] {
    ProgressPrinter printer(true);
    printer(report(1, 16, 0.5));   // drawn
    printer(report(2, 16, 0.55));  // under 0.1 s later: skipped
    printer(report(3, 16, 0.7));   // drawn
    printer(report(16, 16, 0.8));  // the end is always drawn, and ends the line
  });
  close(slave);
  std::string text;
  char buffer[256];
  for (ssize_t n; (n = read(master, buffer, sizeof buffer)) > 0;)
    text.append(buffer, std::size_t(n));
  close(master);
  CHECK(text ==
        "\r[  6%] 0.5 s elapsed, ETA 7.5 s   "
        "\r[ 18%] 0.7 s elapsed, ETA 3.0 s   "
        "\r[100%] 0.8 s elapsed, ETA 0.0 s   \n");
}

// glint-render's report while a scene loads (apps/load_progress.hpp).

namespace {

/// Everything written so far to `file` (a tmpfile another thread prints to).
std::string contents(std::FILE* file) {
  std::string text(1 << 16, '\0');
  const ssize_t got = pread(fileno(file), text.data(), text.size(), 0);
  text.resize(got > 0 ? std::size_t(got) : 0);
  return text;
}

/// Waits, up to a minute (a loaded machine may not run the printer for a while), until `file`
/// holds `text`.
bool eventually_holds(std::FILE* file, const std::string& text) {
  for (int i = 0; i < 6000; ++i) {
    if (contents(file).find(text) != std::string::npos) return true;
    usleep(10000);
  }
  return false;
}

}  // namespace

TEST_CASE("load stages are described with their progress", "[load-progress]") {
  using glint::cli::describe_load_stage;
  using glint::cli::LoadStage;
  CHECK(describe_load_stage(LoadStage::reading, 45) == "reading 45%");
  CHECK(describe_load_stage(LoadStage::reading, -1) == "reading");
  CHECK(describe_load_stage(LoadStage::parsing, 0) == "parsing 0%");
  CHECK(describe_load_stage(LoadStage::building, 1000000) ==
        "building the scene of 1000000 spheres");
}

TEST_CASE("a slow load is reported stage by stage in a log, then its end", "[load-progress]") {
  std::FILE* file = std::tmpfile();
  REQUIRE(file);
  {
    glint::cli::LoadProgress loading(true, "big.scene", file, std::chrono::milliseconds(0),
                                     /*terminal=*/false);
    const glint::SceneReadCallback reader = loading.reader_callback();
    reader({glint::SceneReadProgress::Stage::reading, 0, 0});
    CHECK(eventually_holds(file, "loading big.scene: reading ("));
    reader({glint::SceneReadProgress::Stage::parsing, 57, 100});
    CHECK(eventually_holds(file, "loading big.scene: parsing 50% ("));  // a line per tenth
    loading.building(12);
    CHECK(eventually_holds(file, "loading big.scene: building the scene of 12 spheres ("));
    loading.finished(12);
  }
  const std::string text = contents(file);
  std::fclose(file);
  CHECK_THAT(text, Catch::Matches("(loading big\\.scene: [a-z0-9 %]+ \\([0-9.]+ s\\)\n)+"
                                  "loaded big\\.scene: 12 spheres in [0-9.]+ s\n"));
  // One line per stage and tenth, however often the printer woke up.
  CHECK(text.find("parsing 50%") == text.rfind("parsing 50%"));
}

TEST_CASE("a quick load prints nothing", "[load-progress]") {
  std::FILE* file = std::tmpfile();
  REQUIRE(file);
  {
    glint::cli::LoadProgress loading(true, "small.scene", file, std::chrono::hours(1), false);
    loading.reader_callback()({glint::SceneReadProgress::Stage::parsing, 1, 2});
    loading.building(3);
    usleep(300000);  // the printer wakes up a few times, and stays silent
    loading.finished(3);
  }
  {
    glint::cli::LoadProgress quiet(false, "small.scene", file, std::chrono::milliseconds(0), false);
    quiet.building(3);
    usleep(300000);
    quiet.finished(3);
  }
  CHECK(contents(file).empty());
  std::fclose(file);
}
