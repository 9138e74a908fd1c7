// The patch `volcomp init` writes, applied with the real `patch -p1` to a copy of the
// configuration (LinuxCNC's xyzbc-trt, xyzab-tdr and bridgemill samples, and one of our own): volkins'
// KINEMATICS line, no stock pin left, volkins.tool-offset on the tool-offset signal,
// volkins.update first in the servo thread, every other byte unchanged (CRLF and trailing
// blanks too); what it cannot rewrite is refused with its line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <set>
#include <sstream>

#include "init_test_files.hpp"
#include "vc/init/init.hpp"

namespace vc::init {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The lines of `after` that are not lines of `before`, every line of `before` kept in order
// except those `stock` says the patch may replace or delete (reported as a failure otherwise).
template <typename Stock>
std::set<std::string> added_lines(const std::vector<std::string>& before, const std::vector<std::string>& after,
                                  Stock stock) {
  std::set<std::string> added;
  std::size_t i = 0;
  for (const std::string& line : after) {
    while (i < before.size() && before[i] != line && stock(before[i])) ++i;  // a stock line, replaced or deleted
    if (i < before.size() && before[i] == line) {
      ++i;
      continue;
    }
    added.insert(line);
  }
  EXPECT_EQ(i, before.size()) << "an original line went missing: " << (i < before.size() ? before[i] : "");
  return added;
}

// No HAL command of the configuration (its INI and HAL files, comments aside) names `prefix`.
void expect_no_stock_pin(const fs::path& folder, const std::string& prefix) {
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    if (!entry.is_regular_file()) continue;
    if (entry.path().extension() != ".ini" && entry.path().extension() != ".hal") continue;
    for (const std::string& line : lines_of(test::file_text(entry.path())))
      EXPECT_EQ(line.substr(0, line.find('#')).find(prefix), std::string::npos) << entry.path() << ": " << line;
  }
}

// init on `ini`, its machine file in the folder, the patch applied there.
InitResult init_and_patch(const fs::path& ini, const std::string& machine = "machine.toml") {
  InitResult r = run_init({ini.string(), (ini.parent_path() / machine).string(), "2026-01-01"});
  const fs::path diff = ini.parent_path().parent_path() / (ini.stem().string() + ".diff");
  test::write_file(diff, r.patch.diff);
  EXPECT_EQ(test::apply_patch(ini.parent_path(), diff), 0) << r.patch.diff;
  return r;
}

TEST(ConfigPatch, PutsVolkinsInTheXyzbcSample) {
  if (!test::samples_installed())
    GTEST_SKIP() << "LinuxCNC's sample configurations are not installed (" << test::kSampleConfigs << ")";
  const fs::path original = test::kSampleConfigs / "table-rotary-tilting";
  const fs::path copy = test::scratch_folder("xyzbc_patch") / "table-rotary-tilting";
  fs::copy(original, copy, fs::copy_options::recursive);
  const InitResult r = init_and_patch(copy / "xyzbc-trt.ini", "xyzbc.toml");
  EXPECT_EQ(r.machine_path, "xyzbc.toml");  // inside the folder: relative to it

  const std::vector<std::string> before = lines_of(test::file_text(original / "xyzbc-trt.ini"));
  const std::vector<std::string> after = lines_of(test::file_text(copy / "xyzbc-trt.ini"));
  EXPECT_NE(std::find(after.begin(), after.end(),
                      "KINEMATICS = volkins machine=xyzbc.toml coordinates=xyzbc sparm=identityfirst"),
            after.end());
  EXPECT_NE(std::find(after.begin(), after.end(),
                      "HALCMD = net  :tool-offset  volkins.tool-offset xyzbc-trt-gui.tool-offset"),
            after.end());
  EXPECT_NE(std::find(after.begin(), after.end(), "HALCMD = addf volkins.update servo-thread 1"), after.end());
  // The lines the patch adds or changes, exactly; every other line kept, in order.
  const std::set<std::string> changed{"KINEMATICS = volkins machine=xyzbc.toml coordinates=xyzbc sparm=identityfirst",
                                      "HALCMD = net  :tool-offset  volkins.tool-offset xyzbc-trt-gui.tool-offset",
                                      "HALCMD = net  :x-offset    xyzbc-trt-gui.x-offset",
                                      "HALCMD = net  :z-offset    xyzbc-trt-gui.z-offset",
                                      "# volkins (volcomp init): its update function runs first in the servo thread",
                                      "HALCMD = addf volkins.update servo-thread 1"};
  EXPECT_EQ(added_lines(before, after,
                        [](const std::string& line) {
                          return line.find("xyzbc-trt-kins.") != std::string::npos || line.rfind("KINEMATICS", 0) == 0;
                        }),
            changed);
  // No HAL command of the configuration names a stock pin; every other file is unchanged. (Its
  // remap_subs/centering.ngc reads the rot-point pins guarded by `exists`, and its
  // xyzbc-trt.txt names two: init patches no G-code or notes.)
  expect_no_stock_pin(copy, "xyzbc-trt-kins.");
  for (const auto& entry : fs::recursive_directory_iterator(copy)) {
    if (!entry.is_regular_file()) continue;
    const fs::path twin = original / fs::relative(entry.path(), copy);
    if (entry.path().filename() != "xyzbc-trt.ini" && entry.path().filename() != "xyzbc.toml") {
      EXPECT_EQ(test::file_text(entry.path()), test::file_text(twin)) << entry.path();
    }
  }
}

// The bridgemill (5axiskins): 5axiskins.pivot-length taken off its net (pivotsum stays, its out
// driving nothing), volkins.tool-offset on :tool-len, the signal motion.tooloffset.z drives.
TEST(ConfigPatch, PutsVolkinsInTheBridgemillSample) {
  if (!test::samples_installed())
    GTEST_SKIP() << "LinuxCNC's sample configurations are not installed (" << test::kSampleConfigs << ")";
  const fs::path original = test::kSampleConfigs / "bridgemill";
  const fs::path copy = test::scratch_folder("bridgemill_patch") / "bridgemill";
  fs::copy(original, copy, fs::copy_options::recursive);
  const InitResult r = init_and_patch(copy / "5axis.ini", "5axis.toml");
  EXPECT_EQ(r.patch.kinematics, "volkins machine=5axis.toml coordinates=xyzbcwy world=tcp");

  const auto stock = [](const std::string& line) {
    return line.find("5axiskins.") != std::string::npos || line.find("KINEMATICS = 5axiskins") != std::string::npos;
  };
  EXPECT_EQ(added_lines(lines_of(test::file_text(original / "5axis.ini")),
                        lines_of(test::file_text(copy / "5axis.ini")), stock),
            (std::set<std::string>{" KINEMATICS = volkins machine=5axis.toml coordinates=xyzbcwy world=tcp",
                                   "# volkins (volcomp init): its update function runs first in the servo thread; it "
                                   "takes LinuxCNC's tool length offset",
                                   "HALCMD = addf volkins.update servo-thread 1",
                                   "HALCMD = net :tool-len volkins.tool-offset"}));
  const std::vector<std::string> hal_before = lines_of(test::file_text(original / "5axisgui.hal"));
  const std::vector<std::string> hal_after = lines_of(test::file_text(copy / "5axisgui.hal"));
  EXPECT_EQ(added_lines(hal_before, hal_after, stock), std::set<std::string>{});
  EXPECT_EQ(hal_after.size() + 1, hal_before.size());  // only `net :pivot-len => 5axiskins.pivot-length` went
  EXPECT_NE(std::find(hal_after.begin(), hal_after.end(), "net :pivot-len <= pivotsum.out"), hal_after.end());
  expect_no_stock_pin(copy, "5axiskins.");
  for (const auto& entry : fs::recursive_directory_iterator(copy)) {
    if (!entry.is_regular_file()) continue;
    const std::string name = entry.path().filename().string();
    if (name != "5axis.ini" && name != "5axisgui.hal" && name != "5axis.toml") {
      EXPECT_EQ(test::file_text(entry.path()), test::file_text(original / fs::relative(entry.path(), copy)))
          << entry.path();
    }
  }
}

// The xyzab-tdr sample (xyzab_tdr_kins): its six net lines of stock pins in HALCMDs, five
// deleted (their signals stay on the vismach GUI's and the pyvcp sliders' pins, the sets kept),
// the tool offset's on :tool-offset to volkins; no sparm (type 0 the identity, as volkins').
TEST(ConfigPatch, PutsVolkinsInTheTdrSample) {
  if (!test::samples_installed())
    GTEST_SKIP() << "LinuxCNC's sample configurations are not installed (" << test::kSampleConfigs << ")";
  const fs::path original = test::kSampleConfigs / "table-dual-rotary";
  const fs::path copy = test::scratch_folder("tdr_patch") / "table-dual-rotary";
  fs::copy(original, copy, fs::copy_options::recursive);
  const InitResult r = init_and_patch(copy / "xyzab-tdr.ini", "xyzab-tdr.toml");
  EXPECT_EQ(r.patch.kinematics, "volkins machine=xyzab-tdr.toml coordinates=xyzab");

  const std::vector<std::string> before = lines_of(test::file_text(original / "xyzab-tdr.ini"));
  const std::vector<std::string> after = lines_of(test::file_text(copy / "xyzab-tdr.ini"));
  EXPECT_EQ(added_lines(before, after,
                        [](const std::string& line) {
                          return line.find("xyzab_tdr_kins.") != std::string::npos || line.rfind("KINEMATICS", 0) == 0;
                        }),
            (std::set<std::string>{"KINEMATICS = volkins machine=xyzab-tdr.toml coordinates=xyzab",
                                   "HALCMD = net  :tool-offset  volkins.tool-offset",
                                   "# volkins (volcomp init): its update function runs first in the servo thread",
                                   "HALCMD = addf volkins.update servo-thread 1"}));
  EXPECT_EQ(after.size() + 3, before.size());  // 6 stock nets out (one of them replaced), 2 lines in
  for (const char* kept : {"HALCMD = sets :x-offset     -20", "HALCMD = sets :z-offset     -10"})
    EXPECT_NE(std::find(after.begin(), after.end(), kept), after.end()) << kept;
  expect_no_stock_pin(copy, "xyzab_tdr_kins.");
  // Every other file unchanged (its demos/xyzab-tdr-demo.ngc reads four stock pins: init
  // patches no G-code).
  for (const auto& entry : fs::recursive_directory_iterator(copy)) {
    if (!entry.is_regular_file()) continue;
    const std::string name = entry.path().filename().string();
    if (name != "xyzab-tdr.ini" && name != "xyzab-tdr.toml") {
      EXPECT_EQ(test::file_text(entry.path()), test::file_text(original / fs::relative(entry.path(), copy)))
          << entry.path();
    }
  }
}

TEST(ConfigPatch, RewritesTheConfigurationsOwnHalFilesByteForByte) {
  const fs::path dir = test::scratch_folder("own_hal") / "cfg";
  fs::create_directories(dir / "lib");
  test::write_file(dir / "lib/sim.tcl", "# not read\n");
  ::setenv("HALLIB_DIR", (dir / "lib").c_str(), 1);
  std::string ini =
      "[EMC]\r\nMACHINE = own\r\n[KINS]\r\nKINEMATICS =   xyzac-trt-kins   \r\nJOINTS = 5\r\n"
      "[TRAJ]\r\nCOORDINATES = X Y Z A C\r\nLINEAR_UNITS = mm\r\n"
      "[HAL]\r\nHALFILE = LIB:sim.tcl\r\nHALFILE = kins.hal\r\n[EMCIO]\r\nTOOL_TABLE = t.tbl\r\n";
  const double limits[5][2] = {{-1, 1}, {-2, 2}, {-3, 3}, {-90, 90}, {-36000, 36000}};
  for (int j = 0; j < 5; ++j)
    ini += "[JOINT_" + std::to_string(j) + "]\r\nTYPE = " + (j < 3 ? "LINEAR" : "ANGULAR") +
           "\r\nMIN_LIMIT = " + std::to_string(static_cast<int>(limits[j][0])) +
           "\r\nMAX_LIMIT = " + std::to_string(static_cast<int>(limits[j][1])) + "\r\n";
  test::write_file(dir / "own.ini", ini);
  test::write_file(dir / "t.tbl", "T1 P1 Z50 D6 ;long\nT2 P2 Z75.5 ;longer\n");
  const std::string hal =
      "loadrt xyzac-trt-kins\n"
      "setp xyzac-trt-kins.x-rot-point 10   \n"
      "net :yoff xyzac-trt-kins.y-offset\n"
      "sets :yoff 5 # the y offset\n"
      "net :tool <= motion.tooloffset.z => xyzac-trt-kins.tool-offset\n"
      "xyzac-trt-kins.z-offset = 7\n"
      "net :kt kinstype.is-1 => gui.led  \n"
      "net :xoff gui.xoff <= xyzac-trt-kins.x-offset\n"
      "sets :xoff 1\n"
      "addf motion-controller servo-thread";
  test::write_file(dir / "kins.hal", hal);
  const InitResult r = init_and_patch(dir / "own.ini");
  ::unsetenv("HALLIB_DIR");

  EXPECT_EQ(test::file_text(dir / "kins.hal"),
            "loadrt [KINS]KINEMATICS\n"
            "net :tool <= motion.tooloffset.z => volkins.tool-offset\n"
            "net :kt kinstype.is-1 => gui.led  \n"
            "net :xoff gui.xoff\n"  // the arrow left dangling goes with the pin
            "sets :xoff 1\n"
            "addf motion-controller servo-thread");
  std::string patched_ini = ini;
  patched_ini.replace(patched_ini.find("xyzac-trt-kins   "), 17,
                      "volkins machine=machine.toml coordinates=xyzac world=tcp");
  patched_ini.insert(patched_ini.find("[EMCIO]"),
                     "# volkins (volcomp init): its update function runs first in the servo thread\r\n"
                     "HALCMD = addf volkins.update servo-thread 1\r\n");
  EXPECT_EQ(test::file_text(dir / "own.ini"), patched_ini);
  // The geometry: A's pole [xr, yr + dy, zr + dz], C's [0, -dy, -dz], the fixture [-xr, -yr, -zr].
  const NominalMachine& m = r.machine;
  EXPECT_EQ(m.workpiece_chain[0].pole_mm, (Vector3{10, 5, 7}));
  EXPECT_EQ(m.workpiece_chain[1].pole_mm, (Vector3{0, -5, -7}));
  EXPECT_EQ(m.fixture_origin_mm, (Vector3{-10, 0, 0}));
  EXPECT_EQ(m.tool_length_mm, 75.5);
  EXPECT_NE(r.machine_text.find("tool_length_mm = 75.5             # the longest tool of the tool table, T2: t.tbl:2 "
                                "`T2 P2 Z75.5 ;longer`"),
            std::string::npos)
      << r.machine_text;
  ASSERT_EQ(r.not_read.size(), 1u);
  EXPECT_NE(r.not_read[0].find("sim.tcl"), std::string::npos);
  EXPECT_NE(r.machine_text.find("#   " + (dir / "lib/sim.tcl").string()), std::string::npos) << r.machine_text;
}

TEST(ConfigPatch, RefusesWhatItCannotRewrite) {
  const fs::path dir = test::scratch_folder("cannot");
  const fs::path lib = test::scratch_folder("cannot_lib");
  std::string ini =
      "[KINS]\nKINEMATICS = xyzbc-trt-kins\nJOINTS = 5\n[TRAJ]\nCOORDINATES = XYZBC\nLINEAR_UNITS = mm\n"
      "[HAL]\nHALFILE = m.hal\n";
  for (int j = 0; j < 5; ++j) ini += "[JOINT_" + std::to_string(j) + "]\nMIN_LIMIT = -1\nMAX_LIMIT = 1\n";
  test::write_file(dir / "m.ini", ini);
  auto refusal = [&](const std::string& hal) -> std::string {
    test::write_file(dir / "m.hal", hal);
    try {
      run_init({(dir / "m.ini").string(), (dir / "m.toml").string(), "2026-01-01"});
    } catch (const LoadError& e) {
      return e.what();
    }
    return "accepted";
  };
  EXPECT_EQ(refusal("loadrt [KINS]KINEMATICS\ngetp xyzbc-trt-kins.x-offset\n"),
            (dir / "m.hal").string() +
                ":2: error: `getp xyzbc-trt-kins.x-offset` names xyzbc-trt-kins.x-offset: init "
                "rewrites the setp and net lines of xyzbc-trt-kins pins only; change this one "
                "by hand (volkins has no such pin)");
  EXPECT_EQ(refusal("setp xyzbc-trt-kins.no-such-pin 1\n"),
            (dir / "m.hal").string() + ":1: error: xyzbc-trt-kins has no pin xyzbc-trt-kins.no-such-pin");
  EXPECT_EQ(refusal("net :x other.pin => xyzbc-trt-kins.x-offset\n"),
            (dir / "m.hal").string() +
                ":1: error: xyzbc-trt-kins.x-offset follows other.pin at run time (both are on "
                "signal :x, which no sets gives a value); volkins takes the geometry from the "
                "machine file: set it with setp");
  EXPECT_EQ(refusal("loadrt xyzbc-trt-kins sparm=identityfirst\n"),
            (dir / "m.hal").string() +
                ":1: error: `loadrt xyzbc-trt-kins sparm=identityfirst` loads xyzbc-trt-kins "
                "with other parameters than [KINS]KINEMATICS (m.ini:2 `KINEMATICS = "
                "xyzbc-trt-kins`): make them the same (`loadrt [KINS]KINEMATICS`)");
  // A stock pin in a file outside the configuration folder.
  test::write_file(lib / "outside.hal", "setp xyzbc-trt-kins.x-offset 3\n");
  std::string with_lib = ini;
  with_lib.replace(with_lib.find("HALFILE = m.hal"), 15, "HALFILE = " + (lib / "outside.hal").string());
  test::write_file(dir / "m.ini", with_lib);
  const std::string outside = refusal("");
  EXPECT_EQ(
      outside.rfind((lib / "outside.hal").string() + ":1: error: `setp xyzbc-trt-kins.x-offset 3` sets a "
                                                     "xyzbc-trt-kins pin, in a file outside the configuration folder",
                    0),
      0u)
      << outside;
}

// The golden xyzbc mill (tests/golden/bad_inis/good) in a scratch folder, its INI's HALFILE line
// replaced by `halfiles`; the INI's path.
fs::path golden_mill(const std::string& name, const std::string& halfiles, const std::string& ini_name = "m.ini") {
  const fs::path dir = test::scratch_folder(name);
  std::string ini = test::file_text(test::source_path("tests/golden/bad_inis/good/xyzbc.ini"));
  ini.replace(ini.find("HALFILE = xyzbc.hal\n"), 20, halfiles);
  test::write_file(dir / ini_name, ini);
  return dir / ini_name;
}

constexpr const char* kGoldenGeometry =
    "setp xyzbc-trt-kins.z-rot-point 50\nsetp xyzbc-trt-kins.x-offset -20\nsetp xyzbc-trt-kins.z-offset -15\n";

// A stock pin set in a file run by `source` is seen (the machine file's poles) and patched as in
// any HAL file of the folder; outside the folder it is refused.
TEST(ConfigPatch, PatchesStockPinsInSourcedFiles) {
  const fs::path ini = golden_mill("sourced", "HALFILE = kins.hal\n");
  const fs::path dir = ini.parent_path();
  test::write_file(dir / "kins.hal", "loadrt [KINS]KINEMATICS\nsource geometry.hal\n");
  test::write_file(dir / "geometry.hal", std::string("# the geometry\n") + kGoldenGeometry + "setp other.pin 1\n");
  const InitResult r = init_and_patch(ini);
  EXPECT_EQ(r.machine.workpiece_chain[0].pole_mm, (Vector3{-20, 0, 35}));  // [xr + dx, yr, zr + dz]
  EXPECT_EQ(r.machine.fixture_origin_mm, (Vector3{0, 0, -50}));
  EXPECT_EQ(test::file_text(dir / "geometry.hal"), "# the geometry\nsetp other.pin 1\n");
  EXPECT_EQ(test::file_text(dir / "kins.hal"), "loadrt [KINS]KINEMATICS\nsource geometry.hal\n");
  expect_no_stock_pin(dir, "xyzbc-trt-kins.");

  const fs::path outside = test::scratch_folder("sourced_outside") / "geometry.hal";
  test::write_file(outside, kGoldenGeometry);
  const fs::path second = golden_mill("sourced_from_outside", "HALFILE = kins.hal\n");
  test::write_file(second.parent_path() / "kins.hal", "loadrt [KINS]KINEMATICS\nsource " + outside.string() + "\n");
  try {
    run_init({second.string(), (second.parent_path() / "m.toml").string(), "2026-01-01"});
    ADD_FAILURE() << "a stock pin sourced from outside the folder was accepted";
  } catch (const LoadError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(outside.string() +
                                              ":1: error: `setp xyzbc-trt-kins.z-rot-point 50` sets a xyzbc-trt-kins "
                                              "pin, in a file outside the configuration folder",
                                          0),
              0u)
        << e.what();
  }
}

// The files of a folder, by name: their bytes.
std::map<std::string, std::string> folder_files(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.is_regular_file()) files[entry.path().filename().string()] = test::file_text(entry.path());
  return files;
}

// LinuxCNC's qtplasmac samples include qtplasmac_metric_ini.inc from three INIs: the patch
// leaves it as it is and gives this configuration a copy with the edits; --edit-shared edits it.
TEST(ConfigPatch, CopiesTheQtplasmacIncludeRatherThanChangeItForEveryone) {
  const fs::path original = "/usr/share/doc/linuxcnc/examples/sample-configs/sim/qtplasmac";
  if (!fs::is_directory(original)) GTEST_SKIP() << "LinuxCNC's qtplasmac sample is not installed (" << original << ")";
  const fs::path copy = test::scratch_folder("qtplasmac") / "qtplasmac";
  fs::copy(original, copy, fs::copy_options::recursive);
  const std::map<std::string, std::string> before = folder_files(copy);
  const InitResult r = init_and_patch(copy / "qtplasmac_l_metric.ini");
  const std::map<std::string, std::string> after = folder_files(copy);

  EXPECT_EQ(after.at("qtplasmac_metric_ini.inc"), before.at("qtplasmac_metric_ini.inc"));  // byte for byte
  const std::string& inc = after.at("qtplasmac_metric_ini.volkins.inc");
  EXPECT_NE(inc.find("\nKINEMATICS              = volkins machine=machine.toml coordinates=xyyz\n"), std::string::npos);
  EXPECT_NE(inc.find("\nHALCMD = addf volkins.update servo-thread 1\n"), std::string::npos);
  EXPECT_EQ(inc.find("= trivkins"), std::string::npos);
  std::string ini = before.at("qtplasmac_l_metric.ini");
  ini.replace(ini.find("#INCLUDE qtplasmac_metric_ini.inc"), 33, "#INCLUDE qtplasmac_metric_ini.volkins.inc");
  EXPECT_EQ(after.at("qtplasmac_l_metric.ini"), ini);
  for (const auto& [name, text] : before) {  // the other configurations are unaffected
    if (name != "qtplasmac_l_metric.ini") {
      EXPECT_EQ(after.at(name), text) << name;
    }
  }
  EXPECT_EQ(after.size(), before.size() + 1);  // the copy
  EXPECT_EQ(r.patch.created, std::vector<std::string>{(copy / "qtplasmac_metric_ini.volkins.inc").string()});
  ASSERT_EQ(r.remarks.size(), 1u);
  EXPECT_NE(r.remarks[0].find("qtplasmac_metric_ini.inc is left as it is: an #INCLUDEd file"), std::string::npos);
  EXPECT_NE(r.remarks[0].find("--edit-shared edits it in place"), std::string::npos);
  // The copy read back as the configuration's include: volkins' line where trivkins was.
  const LinuxcncIni patched = LinuxcncIni::read((copy / "qtplasmac_l_metric.ini").string());
  EXPECT_EQ(patched.find("KINS", "KINEMATICS")->value, "volkins machine=machine.toml coordinates=xyyz");

  // --edit-shared: the include edited in place, no copy.
  const fs::path in_place = test::scratch_folder("qtplasmac_in_place") / "qtplasmac";
  fs::copy(original, in_place, fs::copy_options::recursive);
  const InitResult e = run_init(
      {(in_place / "qtplasmac_l_metric.ini").string(), (in_place / "machine.toml").string(), "2026-01-01", true});
  test::write_file(in_place.parent_path() / "edit.diff", e.patch.diff);
  ASSERT_EQ(test::apply_patch(in_place, in_place.parent_path() / "edit.diff"), 0) << e.patch.diff;
  EXPECT_TRUE(e.patch.created.empty());
  EXPECT_EQ(
      "# volcomp init: qtplasmac_l_metric.ini's copy of qtplasmac_metric_ini.inc (other configurations use "
      "that one), volkins in place of trivkins\n" +
          test::file_text(in_place / "qtplasmac_metric_ini.inc"),
      inc);
  EXPECT_EQ(test::file_text(in_place / "qtplasmac_l_metric.ini"), before.at("qtplasmac_l_metric.ini"));
  EXPECT_FALSE(fs::exists(in_place / "qtplasmac_metric_ini.volkins.inc"));
}

// A HAL file another INI of the folder names (HALFILE, or a HALCMD's source) gets a copy; the
// line of this configuration that names it (a HALFILE, a source in its own HAL file) names the
// copy; a HAL file only this INI uses is edited in place.
TEST(ConfigPatch, CopiesAHalFileAnotherConfigurationUses) {
  const fs::path ini = golden_mill("shared_hal", "HALFILE = shared.hal\nHALFILE = own.hal\n", "a.ini");
  const fs::path dir = ini.parent_path();
  test::write_file(dir / "shared.hal", "loadrt [KINS]KINEMATICS\nsetp xyzbc-trt-kins.z-rot-point 50\n");
  test::write_file(dir / "own.hal", "setp xyzbc-trt-kins.x-offset -20\nsource geo.hal\n");
  test::write_file(dir / "geo.hal", "setp xyzbc-trt-kins.z-offset -15\n");
  test::write_file(dir / "shared.volkins.hal", "# someone else's file of that name\n");
  std::string other = test::file_text(ini);
  other.replace(other.find("HALFILE = shared.hal\nHALFILE = own.hal\n"), 38,
                "HALFILE = shared.hal\nHALCMD = source geo.hal\n");
  test::write_file(dir / "b.ini", other);
  const std::map<std::string, std::string> before = folder_files(dir);
  const InitResult r = init_and_patch(ini);
  const std::map<std::string, std::string> after = folder_files(dir);

  EXPECT_EQ(r.machine.workpiece_chain[0].pole_mm, (Vector3{-20, 0, 35}));
  for (const char* unchanged : {"shared.hal", "geo.hal", "b.ini", "shared.volkins.hal"})
    EXPECT_EQ(after.at(unchanged), before.at(unchanged)) << unchanged;
  const std::string header = "# volcomp init: a.ini's copy of ";
  const std::string tail = " (other configurations use that one), volkins in place of xyzbc-trt-kins\n";
  EXPECT_EQ(after.at("shared.volkins-2.hal"), header + "shared.hal" + tail + "loadrt [KINS]KINEMATICS\n");  // free name
  EXPECT_EQ(after.at("geo.volkins.hal"), header + "geo.hal" + tail);  // every line went
  EXPECT_EQ(after.at("own.hal"), "source geo.volkins.hal\n");         // this INI's only: in place
  EXPECT_NE(after.at("a.ini").find("HALFILE = shared.volkins-2.hal\nHALFILE = own.hal\n"), std::string::npos);
  EXPECT_EQ(after.at("a.ini").find("xyzbc-trt-kins."), std::string::npos);
  EXPECT_EQ(after.size(), before.size() + 2);  // the two copies

  // --edit-shared: the same folder as it was, edited in place, no copy.
  const fs::path again = test::scratch_folder("shared_hal_in_place");
  for (const auto& [name, text] : before) test::write_file(again / name, text);
  const InitResult e = run_init({(again / "a.ini").string(), (again / "machine.toml").string(), "2026-01-01", true});
  test::write_file(again.parent_path() / "in_place.diff", e.patch.diff);
  ASSERT_EQ(test::apply_patch(again, again.parent_path() / "in_place.diff"), 0) << e.patch.diff;
  EXPECT_TRUE(e.patch.created.empty());
  EXPECT_EQ(folder_files(again).size(), before.size());
  EXPECT_EQ(test::file_text(again / "shared.hal"), "loadrt [KINS]KINEMATICS\n");
  EXPECT_EQ(test::file_text(again / "geo.hal"), "");
  EXPECT_EQ(test::file_text(again / "own.hal"), "source geo.hal\n");
}

}  // namespace
}  // namespace vc::init
