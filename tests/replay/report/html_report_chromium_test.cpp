// Opens a generated report in headless Chromium (Debian's `chromium`, installed by the set-up)
// and checks that it renders: its pictures are in the DOM with their drawn content, the summary
// values are there, escaped text did not run, and the screenshot is not blank. Without
// Chromium the test fails, unless RCSIM_NO_CHROMIUM=1 says to skip it.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>

#include "replay/report/html_report.hpp"
#include "replay/store/report_store.hpp"
#include "replay/replay_fixtures.hpp"

namespace rcsim::replay {
namespace {

namespace fs = std::filesystem;

using testing::count_occurrences;
using testing::read_file;


class HtmlReportChromium : public ::testing::Test {
 protected:
  void SetUp() override {
    const char* skip = std::getenv("RCSIM_NO_CHROMIUM");
    if (skip != nullptr && std::string(skip) == "1") GTEST_SKIP() << "RCSIM_NO_CHROMIUM=1";
    for (const char* candidate : {"/usr/bin/chromium", "/usr/bin/chromium-browser", "/usr/bin/google-chrome"}) {
      if (fs::exists(candidate)) {
        browser_ = candidate;
        break;
      }
    }
    ASSERT_FALSE(browser_.empty()) << "headless Chromium is required for this test (Debian package `chromium`); "
                                      "install it, or set RCSIM_NO_CHROMIUM=1 to skip";
    dir_ = fs::temp_directory_path() / ("rcsim_chromium_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "home");
  }
  void TearDown() override {
    if (!dir_.empty()) fs::remove_all(dir_);
  }

  // Runs Chromium headless on a file with the given mode arguments; stdout goes to `stdout_path`.
  int chromium(const fs::path& page, const std::string& mode, const fs::path& stdout_path) {
    const std::string profile = (dir_ / ("profile_" + std::to_string(runs_++))).string();
    const std::string command = "HOME=" + (dir_ / "home").string() + " timeout 90 " + browser_ +
                                " --headless=new --no-sandbox --disable-gpu --disable-dev-shm-usage "
                                "--no-first-run --hide-scrollbars --user-data-dir=" +
                                profile + " " + mode + " file://" + page.string() + " > " + stdout_path.string() +
                                " 2> " + (dir_ / "chromium.log").string();
    const int status = std::system(command.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

  std::string browser_;
  fs::path dir_;
  int runs_ = 0;
};

TEST_F(HtmlReportChromium, RendersPicturesTablesAndNoInjectedScript) {
  const std::string db_path = (dir_ / "r.sqlite").string();
  std::int64_t targets_recorded = 0;
  {
    const auto db = open_report_database(db_path, true);
    const Scene scene = testing::two_cars_scene(3.0);
    Recording rec = testing::model_recording(scene, 5);
    rec.dir = dir_ / "rec";
    rec.name = "<script>document.title='pwned'</script> & \"x\"";
    rec.objects[0].id = "<img src=x onerror=\"document.body.setAttribute('data-pwned','1')\">";
    ReplayOptions options;
    options.seed = 6;
    options.import.effects = {};
    ReportWriter writer(*db);
    targets_recorded = replay_recording(rec, options, writer).targets_recorded;
  }
  const fs::path page = dir_ / "report.html";
  HtmlReportOptions options;
  write_html_report_file(db_path, page.string(), options);
  const std::string html = read_file(page);
  const std::size_t svgs_in_file = testing::count_occurrences(html, "<svg class=");

  const fs::path dom_path = dir_ / "dom.html";
  ASSERT_EQ(chromium(page, "--dump-dom", dom_path), 0) << read_file(dir_ / "chromium.log");
  const std::string dom = read_file(dom_path);
  ASSERT_GT(dom.size(), 1000u) << read_file(dir_ / "chromium.log");
  // Every picture was parsed as SVG, with its drawn content.
  EXPECT_EQ(testing::count_occurrences(dom, "<svg class="), svgs_in_file);
  EXPECT_GE(testing::count_occurrences(dom, "<svg class=\"birdseye\""), 3u);
  // Two sensors with four series each; the detection rate against range; the background range and azimuth.
  EXPECT_EQ(testing::count_occurrences(dom, "<svg class=\"plot\""), 11u);
  EXPECT_GE(testing::count_occurrences(dom, "<svg class=\"object-frame\""), 1u);
  EXPECT_EQ(testing::count_occurrences(dom, "<svg class=\"histogram\""), 4u);
  EXPECT_GT(testing::count_occurrences(dom, "<circle class=\"t rec current\""), 5u);
  EXPECT_GT(testing::count_occurrences(dom, "<polygon class=\"t sim current\""), 5u);
  EXPECT_GE(testing::count_occurrences(dom, "<polygon class=\"fov\""), 6u);
  EXPECT_GE(testing::count_occurrences(dom, "<polygon class=\"box\""), 3u);
  EXPECT_GT(testing::count_occurrences(dom, "<rect class=\"bar\""), 4u);
  // The verdict is the first thing under each run's title, as the browser laid the page out: the
  // title's mark, then the verdict block with the track tolerances' headline figure first.
  std::size_t sections = 0;
  for (std::size_t at = dom.find("<section class=\"run\""); at != std::string::npos;
       at = dom.find("<section class=\"run\"", at + 1)) {
    ++sections;
    const std::size_t title_end = dom.find("</h2>", at);
    ASSERT_NE(title_end, std::string::npos);
    const std::string title = dom.substr(at, title_end - at);
    EXPECT_TRUE(title.find("<span class=\"mark pass\">PASS</span>") != std::string::npos ||
                title.find("<span class=\"mark fail\">FAIL</span>") != std::string::npos)
        << title;
    const std::string next = dom.substr(title_end + 5, 120);
    EXPECT_EQ(next.rfind("<div class=\"verdict ", 0), 0u) << next;
    const std::size_t first_row = dom.find("<tr class=", title_end);
    ASSERT_NE(first_row, std::string::npos);
    EXPECT_NE(dom.substr(first_row, 120).find(">gospa_mean_m<"), std::string::npos) << dom.substr(first_row, 120);
  }
  EXPECT_EQ(sections, 1u);
  // The summary value, as parsed by the browser.
  EXPECT_NE(dom.find("data-key=\"targets_recorded\">" + std::to_string(targets_recorded) + "<"), std::string::npos);
  // Escaped text stayed text: no script element, no image, the handlers never ran.
  EXPECT_EQ(dom.find("<script"), std::string::npos);
  EXPECT_EQ(dom.find("<img"), std::string::npos);
  EXPECT_EQ(dom.find("<body data-pwned"), std::string::npos);
  EXPECT_EQ(dom.find("<title>pwned"), std::string::npos);
  EXPECT_NE(dom.find("&lt;script&gt;document.title='pwned'&lt;/script&gt; &amp; \"x\""), std::string::npos);

  // A screenshot: a PNG, and much more than the same window of a blank page.
  const fs::path shot = dir_ / "report.png", blank_shot = dir_ / "blank.png", blank_page = dir_ / "blank.html";
  std::ofstream(blank_page) << "<!DOCTYPE html><html><body></body></html>\n";
  ASSERT_EQ(chromium(page, "--window-size=1280,2000 --screenshot=" + shot.string(), dir_ / "out1.txt"), 0)
      << read_file(dir_ / "chromium.log");
  ASSERT_EQ(chromium(blank_page, "--window-size=1280,2000 --screenshot=" + blank_shot.string(), dir_ / "out2.txt"), 0)
      << read_file(dir_ / "chromium.log");
  ASSERT_TRUE(fs::exists(shot));
  ASSERT_TRUE(fs::exists(blank_shot));
  const std::string png = read_file(shot);
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_GT(fs::file_size(shot), 5 * fs::file_size(blank_shot))
      << "screenshot " << fs::file_size(shot) << " bytes, blank page " << fs::file_size(blank_shot) << " bytes";
  // To look at it: RCSIM_KEEP_SCREENSHOT=/tmp/report.png keeps the screenshot, the page and the database.
  if (const char* keep = std::getenv("RCSIM_KEEP_SCREENSHOT")) {
    const fs::path target(keep);
    fs::copy_file(shot, target, fs::copy_options::overwrite_existing);
    fs::copy_file(page, fs::path(target).replace_extension(".html"), fs::copy_options::overwrite_existing);
    fs::copy_file(db_path, fs::path(target).replace_extension(".sqlite"), fs::copy_options::overwrite_existing);
  }
}

}  // namespace
}  // namespace rcsim::replay
