// What the report's tests share (tests/report): scratch folders, headless chromium on a page
// (with a probe that reports every picture decoded and every request made, and the page's own
// console messages), and a report that must be refused without touching the page at -o.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.hpp"

namespace vc::test {

namespace fs = std::filesystem;

inline fs::path scratch(const std::string& name) {
  const fs::path f = fs::temp_directory_path() / ("vc_report_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(f);
  fs::create_directories(f);
  return f;
}

inline void write(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

inline std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

inline bool have_chromium() { return run_command("command -v chromium >/dev/null 2>&1").exit_code == 0; }

#define SKIP_WITHOUT_CHROMIUM()                                                                             \
  if (!::vc::test::have_chromium())                                                                         \
  GTEST_SKIP() << "chromium is not installed (apt-get install --no-install-recommends chromium; .ci/setup " \
                  "installs it): the report is not checked in a browser"

// Headless chromium on `page` with `options`; its messages (stderr) go to `log`. As root it
// needs --no-sandbox; its own profile folder keeps runs apart.
inline CommandResult chromium(const std::string& options, const fs::path& page, const fs::path& log) {
  const fs::path profile = scratch("chromium_profile");
  const CommandResult r = run_command(
      "timeout 180 chromium --headless --no-sandbox --disable-gpu --no-first-run --user-data-dir='" + profile.string() +
      "' --enable-logging=stderr --v=0 " + options + " 'file://" + page.string() + "' 2>'" + log.string() + "'");
  fs::remove_all(profile);
  return r;
}

// What the page itself logged (console messages, uncaught errors) or failed to load: chromium
// prints these as "CONSOLE" lines and net::ERR_ codes. Its own complaints about the machine
// (no D-Bus, no GPU) are not the page's.
inline std::vector<std::string> page_messages(const fs::path& log) {
  std::vector<std::string> found;
  std::istringstream lines(file_text(log));
  for (std::string line; std::getline(lines, line);)
    if (line.find("CONSOLE") != std::string::npos || line.find("net::ERR_") != std::string::npos ||
        line.find("Uncaught") != std::string::npos)
      found.push_back(line);
  return found;
}

// A copy of the page with a probe at its end: after the load event it writes into the DOM how
// many pictures there are, how many decoded (naturalWidth > 0), and every resource the page
// fetched that is not a data: URI (performance entries), which --dump-dom then shows.
inline fs::path probed_copy(const fs::path& page, const fs::path& folder) {
  const std::string probe = R"(<script>
window.addEventListener('load', function () {
  var images = Array.prototype.slice.call(document.images);
  var decoded = images.filter(function (i) { return i.complete && i.naturalWidth > 0; }).length;
  var fetched = performance.getEntriesByType('resource').map(function (e) { return e.name; })
      .filter(function (n) { return n.indexOf('data:') !== 0; });
  var p = document.createElement('pre');
  p.id = 'vc-probe';
  p.textContent = 'images=' + images.length + ' decoded=' + decoded + ' fetched=' + fetched.length + ' [' + fetched.join(' ') + ']';
  document.body.appendChild(p);
});
</script>
)";
  std::string html = file_text(page);
  const std::size_t end = html.rfind("</body>");
  html.insert(end == std::string::npos ? html.size() : end, probe);
  const fs::path copy = folder / "probed.html";
  write(copy, html);
  return copy;
}

// What the probe of probed_copy wrote into the DOM that --dump-dom printed ("images=N decoded=N
// fetched=0 []"), or "the probe did not run: " and the DOM's start.
inline std::string probe_report(const std::string& dom) {
  const std::string start = "<pre id=\"vc-probe\">";
  const std::size_t at = dom.find(start);
  if (at == std::string::npos) return "the probe did not run: " + dom.substr(0, 300);
  const std::size_t from = at + start.size();
  return dom.substr(from, dom.find("</pre>", from) - from);
}

// Runs a report that must fail: non-zero exit, `message` in what it printed, and the page at
// -o as it was before (absent, or an older page left untouched).
inline void expect_refused(const std::string& arguments, const std::string& message, const fs::path& page) {
  const std::string before = fs::exists(page) ? file_text(page) : std::string("(none)");
  const CommandResult r = run_volcomp("report " + arguments + " -o " + page.string());
  EXPECT_NE(r.exit_code, 0) << arguments;
  EXPECT_NE(r.out.find(message), std::string::npos) << "expected \"" << message << "\" in: " << r.out;
  EXPECT_EQ(fs::exists(page) ? file_text(page) : std::string("(none)"), before) << "the page was written or changed";
  // No temporary left beside it either.
  for (const auto& entry : fs::directory_iterator(page.parent_path()))
    EXPECT_NE(entry.path().filename().string().rfind("." + page.filename().string(), 0), 0u) << entry.path();
}

}  // namespace vc::test
