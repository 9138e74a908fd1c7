#include "vc/report/accuracy_report.hpp"

#include <algorithm>
#include <cctype>
#include <ctime>
#include <fstream>
#include <sstream>

#include "report_style.hpp"
#include "vc/identify/balance.hpp"
#include "vc/machine/compensation_types.hpp"
#include "vc/plot/machine_plot.hpp"
#include "vc/plot/volume_map.hpp"
#include "vc/plot/volume_map_plot.hpp"
#include "vc/report/acceptance_section.hpp"
#include "vc/report/drawings.hpp"
#include "vc/report/html.hpp"
#include "vc/report/measurements.hpp"
#include "vc/report/sha256.hpp"

namespace vc::report {
namespace {

// The first page's summary: the figures a reader looks for first, gathered from the sections.
using Summary = std::vector<std::vector<std::string>>;

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char text[40];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M:%S UTC", &tm);
  return text;
}

// The page's parts, each a <section> (a printed page of its own) with an id for the contents.
class Page {
 public:
  void section(const std::string& id, const std::string& title, const std::string& body) {
    contents_.emplace_back(id, title);
    body_ += "<section id=\"" + id + "\">\n<h2>" + escaped(title) + "</h2>\n" + body + "</section>\n";
  }
  int sections() const { return static_cast<int>(contents_.size()); }
  std::string html(const std::string& title, const std::string& header) const {
    std::string nav = "<nav><ol>\n";
    for (const auto& [id, name] : contents_) nav += "<li><a href=\"#" + id + "\">" + escaped(name) + "</a></li>\n";
    nav += "</ol></nav>\n";
    return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" + escaped(title) +
           "</title>\n<style>" + kReportStyle + "</style>\n</head>\n<body>\n<header>\n<h1>" + escaped(title) +
           "</h1>\n" + header + nav + "</header>\n" + body_ + "</body>\n</html>\n";
  }

 private:
  std::vector<std::pair<std::string, std::string>> contents_;
  std::string body_;
};

std::string machine_section(const machine::Model& model) {
  std::vector<std::vector<std::string>> rows = {
      {"name", model.info.name},
      {"serial", model.info.serial},
      {"description", model.info.description},
      {"machine file", shown_path(model.path)},
      {"measured", model.info.measured_on},
      {"instrument", model.info.instrument},
      {"temperature during measurement", fixed(model.info.temperature_C, 1) + " degC"},
      {"tool length L of the file", fixed(model.tool_length_mm, 1) + " mm"}};
  std::string html = html_table({}, rows, false);
  html +=
      "<h3>Files and their SHA-256 checksums</h3>\n<p class=\"note\">The report was made from exactly these files: "
      "<code>sha256sum FILE</code> prints the same checksum.</p>\n";
  std::string files = "<table>\n<thead><tr><th>file</th><th>what</th><th>SHA-256</th></tr></thead>\n<tbody>\n";
  const auto file_row = [&](const std::string& path, const std::string& what) {
    files += "<tr><td>" + escaped(shown_path(path)) + "</td><td>" + escaped(what) + "</td><td class=\"hash\">" +
             sha256_file_hex(path) + "</td></tr>\n";
  };
  file_row(model.path, "machine file");
  std::vector<std::string> seen;  // a table file used by two axes is listed once
  for (const machine::BoundTable& t : model.tables) {
    if (std::find(seen.begin(), seen.end(), t.table.path()) != seen.end()) continue;
    seen.push_back(t.table.path());
    std::string over;
    for (const tables::GridVariable& g : t.table.grid()) over += (over.empty() ? "" : ", ") + g.name();
    file_row(t.table.path(), "error table over " + over);
  }
  html += files + "</tbody></table>\n";
  std::vector<std::vector<std::string>> axes;
  for (const machine::Axis& a : model.axes) {
    const bool rotary = a.type == machine::AxisType::Rotary;
    const std::string unit = rotary ? " deg" : " mm";
    axes.push_back({std::string(1, a.letter), rotary ? "rotary" : "linear",
                    a.chain == machine::Chain::Tool ? "tool chain" : "workpiece chain",
                    fixed(a.travel_min, 1) + unit + " .. " + fixed(a.travel_max, 1) + unit,
                    std::to_string(a.tables.size())});
  }
  html += "<h3>Axes</h3>\n" + html_table({"axis", "type", "chain", "travel", "tables"}, axes, false);
  for (const Warning& w : model.warnings) html += "<p class=\"note\">" + escaped(w.to_string()) + "</p>\n";
  return html;
}

std::string tables_section(const machine::Model& model, const Drawings& drawings, int& figures,
                           std::ostream& progress) {
  std::string html =
      "<p>Each axis's component errors against its position, as the compensation uses them (the table file's units "
      "converted, the machine file's <code>scale</code> and <code>measured_at_mm</code> applied): translations in um, "
      "rotations in arcsec (urad where the files are in urad, mrad or rad). Points are the table's nodes; dashed "
      "lines mark the axis's travel (<code>volcomp plot</code>, preproc/plot/README.md).</p>\n";
  for (int joint = 0; joint < model.joint_count(); ++joint) {
    const machine::Axis& axis = model.axes[static_cast<std::size_t>(joint)];
    const std::string letter(1, static_cast<char>(std::tolower(static_cast<unsigned char>(axis.letter))));
    const plot::AxisPlot p = plot::axis_plot(model, joint, drawings.path(letter + "_axis.png"));
    if (p.drawn) {
      html += html_png_figure(drawings.png(p.figure), "component errors of axis " + std::string(1, axis.letter),
                              "Axis " + std::string(1, axis.letter) + ": component errors against its position.");
      ++figures;
    } else {
      html += "<p class=\"note\">Axis " + std::string(1, axis.letter) + ": no table over its own position alone.</p>\n";
    }
    for (const std::string& n : p.not_drawn)
      html += "<p class=\"note\">Axis " + std::string(1, axis.letter) + ", not drawn: " + escaped(n) + "</p>\n";
  }
  progress << "  error tables drawn\n";
  return html;
}

// The comment on the machine file's line that sets `symbol` (EX0C_um = ... # comment): where
// the value came from, e.g. "volcomp identify sphere from probe.txt +- 0.44 um (standard
// uncertainty)"; empty if the file has no such line or no comment on it.
std::string location_comment(const std::vector<std::string>& lines, const std::string& symbol) {
  for (const std::string& line : lines) {
    const std::size_t start = line.find_first_not_of(" \t");
    if (start == std::string::npos || line.compare(start, symbol.size() + 1, symbol + "_") != 0) continue;
    const std::size_t hash = line.find('#');
    return hash == std::string::npos ? std::string() : line.substr(line.find_first_not_of(" #", hash));
  }
  return {};
}

std::string location_section(const machine::Model& model) {
  std::vector<std::string> lines;
  std::ifstream file(model.path);
  for (std::string line; std::getline(file, line);) lines.push_back(line);
  std::vector<std::vector<std::string>> rows;
  for (const plot::LocationRow& r : plot::location_errors(model))
    rows.push_back({r.line, r.symbol, r.meaning, r.value == 0.0 ? "0" : fixed(r.value, 3), r.unit,
                    r.value == 0.0 ? "" : location_comment(lines, r.symbol)});
  return "<p>Every location error of every axis line and of the spindle line (ISO 230-1 symbols): lengths in um, "
         "angles in arcsec; 0 means the error is not in the machine file. Where from: the machine file's comment on "
         "the value's line (an identification writes its source and standard uncertainty there).</p>\n" +
         html_table({"line", "symbol", "meaning", "value", "unit", "where from"}, rows, false);
}

// The ISO/TR 16907 Annex A types the machine file provides (compensation_types.hpp): one row
// a type with what provides it, then the tool direction and thermal compensation; the codes
// provided in full go to the summary.
std::string compensation_section(const machine::Model& model, Summary& summary) {
  const machine::CompensationTypes types = machine::compensation_types(model);
  std::vector<std::vector<std::string>> rows;
  std::string declared;
  const auto joined = [](const std::vector<std::string>& parts, const char* between) {
    std::string s;
    for (const std::string& p : parts) s += (s.empty() ? "" : between) + p;
    return s;
  };
  for (const machine::CompensationType& t : types.types) {
    const bool composite = t.code.find("VOL") != std::string::npos;
    std::string by =
        composite ? (t.complete ? "complete: " : "partial: has ") + joined(t.sources, " + ") : joined(t.sources, "; ");
    if (!t.missing.empty()) by += "; lacks " + joined(t.missing, ", ");
    rows.push_back({t.code, t.name, by});
    if (t.complete) declared += (declared.empty() ? "" : ", ") + t.code;
  }
  rows.push_back({"tool direction", "FOR " + std::string(types.orientation_possible ? "possible" : "not possible"),
                  types.orientation_reason});
  rows.push_back({"thermal", "not an Annex A type", types.thermal.empty() ? "none" : joined(types.thermal, "; ")});
  summary.push_back({"compensation types (ISO/TR 16907 Annex A)", declared.empty() ? "none" : declared});
  return "<p>The compensation types of ISO/TR 16907 Annex A that the machine file's non-zero terms provide, each "
         "with the axis and the ISO 230-1 symbols that provide it (and their table); a composite type (L-VOL, "
         "R-VOL and their + forms) is complete only with all its parts. L-SPEC and R-SPEC hold the file's terms "
         "the Annex does not name. Thermal compensation is no Annex type; the TR asks that it be active while the "
         "geometric errors are measured.</p>\n" +
         html_table({"type", "what it compensates", "provided by"}, rows, false);
}

// The accuracy balance's largest effects: a table and a bar chart of M and RMS.
std::string balance_section(const machine::Model& model, const Drawings& drawings, int& figures, std::ostream& progress,
                            Summary& summary) {
  const identify::Balance b = identify::accuracy_balance(model, {});
  constexpr std::size_t kTop = 15;
  const std::size_t shown = std::min(kTop, b.effects.size());
  std::vector<std::vector<std::string>> rows;
  std::ostringstream data;
  data << "# accuracy balance of " << model.info.name << ": the " << shown << " largest effects, " << b.poses
       << " poses, L = " << fixed(b.tool_length_mm, 1) << " mm\ndeviation,M[um],RMS[um]\n";
  for (std::size_t k = 0; k < shown; ++k) {
    const identify::DeviationEffect& e = b.effects[k];
    rows.push_back({e.symbol, fixed(e.max_um, 2), fixed(e.delta_um, 2), fixed(e.rms_um, 2), fixed(e.share * 100, 1),
                    fixed(e.max_urad, 1)});
    data << e.symbol << ',' << fixed(e.max_um, 4) << ',' << fixed(e.rms_um, 4) << '\n';
  }
  std::ostringstream gp;
  gp << "set datafile separator ','\nset style data histograms\nset style histogram clustered gap 1\n"
     << "set style fill solid 0.8 border -1\nset boxwidth 0.9\nset grid ytics\nset key top right\n"
     << "set title "
     << plot::text_literal("Accuracy balance of " + model.info.name + ": the " + std::to_string(shown) +
                           " largest effects, each deviation alone at the tool tip (L = " + fixed(b.tool_length_mm, 0) +
                           " mm)")
     << "\nset ylabel 'tool-tip error (um)'\nset xtics rotate by -45 font 'sans,11'\n"
     << "plot DATA every ::1 using 2:xtic(1) title 'M = max |error|' lc rgb '#c0392b', "
     << "'' every ::1 using 3 title 'RMS' lc rgb '#2e86c1'\n";
  const std::string png = drawings.png({drawings.path("balance.png"), data.str(), gp.str(), 1400, 700});
  ++figures;
  summary.push_back({"all deviations together (accuracy balance, L = " + fixed(b.tool_length_mm, 1) + " mm)",
                     "M " + fixed(b.total.max_um, 1) + " um, RMS " + fixed(b.total.rms_um, 1) + " um"});
  std::string largest;
  for (std::size_t k = 0; k < std::min<std::size_t>(3, b.effects.size()); ++k)
    largest += (k ? ", " : "") + b.effects[k].symbol + " " + fixed(b.effects[k].max_um, 1) + " um";
  summary.push_back({"largest single deviations (measure these first)", largest});
  progress << "  accuracy balance: " << b.effects.size() << " deviations over " << b.poses << " poses\n";
  return "<p>Each deviation alone at the tool tip over the travel (" + std::to_string(b.poses) +
         " poses, 5 positions per joint, L = " + fixed(b.tool_length_mm, 1) +
         " mm), largest first: measure the top of the list first (<code>volcomp balance</code>). M = max |error|, "
         "delta = M - min |error| (the source's criteria), share = RMS^2 over the sum of all RMS^2.</p>\n"
         "<p>All deviations together: M " +
         fixed(b.total.max_um, 2) + " um, RMS " + fixed(b.total.rms_um, 2) + " um, tool direction up to " +
         fixed(b.total.max_urad, 1) + " urad.</p>\n" +
         html_table({"deviation", "M [um]", "delta [um]", "RMS [um]", "share [%]", "direction [urad]"}, rows) +
         html_png_figure(png, "accuracy balance bar chart",
                         "The " + std::to_string(shown) + " largest effects: M and RMS of each deviation alone, um.");
}

std::string volume_section(const machine::Model& model, const ReportOptions& options, const Drawings& drawings,
                           int& figures, std::ostream& progress, Summary& summary) {
  plot::VolumeMapOptions o;
  o.tool_lengths_mm = options.tool_lengths_mm;
  if (o.tool_lengths_mm.empty()) o.tool_lengths_mm = {0.0, model.tool_length_mm};
  const plot::VolumeMap map = plot::volume_map(model, o);
  progress << "  volume map: " << map.poses << " poses, " << fixed(map.seconds, 1) << " s\n";
  const std::string x(1, model.axes[static_cast<std::size_t>(map.first_joint)].letter),
      y(1, model.axes[static_cast<std::size_t>(map.second_joint)].letter),
      z(1, model.axes[static_cast<std::size_t>(map.level_joint)].letter);
  std::string levels;
  for (const double l : map.levels_mm) levels += (levels.empty() ? "" : ", ") + fixed(l, 1);
  std::string html =
      "<p>The tool-tip error |e| = |real tip - ideal tip| (um, computed on the model: every table and location "
      "error) over " +
      x + "-" + y + " (" + std::to_string(map.first_mm.size()) + " x " + std::to_string(map.second_mm.size()) +
      " positions over the travel) at " + z + " = " + levels +
      " mm, per tool length, with the rotary axes at 0 and at their worst position (the rotary setting, in 15 deg "
      "steps, whose largest uncompensated |e| over the linear travel is largest). Rows of each picture: no "
      "compensation; " +
      (map.controller_title.empty() ? std::string("-") : map.controller_title) +
      "'s own tables filled by the usual practice (each table its own measured deviation, negated) and by the "
      "modified method (all tables chosen together to make the largest tool-tip error smallest; fitted over these tool "
      "lengths, judged here on the map's poses, which it was not fitted on; <code>volcomp fit-tables</code>, "
      "preproc/fit_tables/README.md). All panels of a picture share one colour scale.</p>\n";
  html += "<p class=\"statement\">" + escaped(plot::full_correction_statement(map)) + "</p>\n";
  std::vector<std::vector<std::string>> rows;
  for (const plot::MapSheet& s : map.sheets) {
    std::vector<std::string> row = {fixed(s.tool_length_mm, 1), s.rotary.label + (s.rotary.worst ? " (worst)" : "")};
    for (const double m : s.max_um) row.push_back(fixed(m, 1));
    if (s.max_um.size() == 3) row.push_back(s.max_um[1] > 0 ? fixed(s.max_um[2] / s.max_um[1], 2) : "-");
    rows.push_back(row);
  }
  std::vector<std::string> header = {"L [mm]", "rotary axes"};
  for (const std::string& c : map.compensations) header.push_back("max |e|, " + c + " [um]");
  if (map.compensations.size() == 3) header.push_back("modified / usual");
  html += "<h3>Largest tool-tip error over each sheet</h3>\n" + html_table(header, rows);
  // The summary: per compensation its largest |e| over every sheet, and where.
  for (std::size_t c = 0; c < map.compensations.size(); ++c) {
    const auto worst =
        std::max_element(map.sheets.begin(), map.sheets.end(),
                         [&](const plot::MapSheet& a, const plot::MapSheet& b) { return a.max_um[c] < b.max_um[c]; });
    summary.push_back({"largest tool-tip error over the volume, " +
                           (c == 0 ? std::string("no compensation")
                                   : map.controller_title + " tables by the " + map.compensations[c]),
                       fixed(worst->max_um[c], 1) + " um (L = " + fixed(worst->tool_length_mm, 1) + " mm, " +
                           worst->rotary.label + ")"});
  }
  summary.push_back({"with volkins (full correction)", plot::full_correction_statement(map)});
  for (std::size_t s = 0; s < map.sheets.size(); ++s) {
    const plot::MapSheet& sheet = map.sheets[s];
    const std::string name = plot::volume_map_name(sheet);
    html += html_png_figure(
        drawings.png(plot::volume_map_plot(map, s, model, drawings.path(name + ".png"))), "volume map " + name,
        "Tool-tip error |e| (um) over " + x + "-" + y + ", L = " + fixed(sheet.tool_length_mm, 1) + " mm, " +
            sheet.rotary.label + (sheet.rotary.worst ? " (the worst rotary position)" : "") + ".",
        FigureSize::Full);
    ++figures;
  }
  return html;
}

std::string measurements_section(const Measurements& found, const std::vector<std::string>& pngs) {
  std::string html =
      "<p>Laser interferometer runs evaluated as ISO 230-2 does (runs that disagree with the others left out, "
      "named) and circular tests as ISO 230-4 does, exactly as <code>volcomp identify laser</code> and "
      "<code>volcomp identify circle</code> evaluate them (preproc/identify/README.md).</p>\n";
  if (found.found.empty()) html += "<p class=\"note\">No laser runs or circular tests in the folder.</p>\n";
  for (std::size_t k = 0; k < found.found.size(); ++k) {
    const Measurement& m = found.found[k];
    html += "<div class=\"measurement\">\n<h3>" + escaped(m.title) + "</h3>\n<p class=\"note\">" +
            escaped(shown_path(m.path)) + " <span class=\"hash\">sha256 " + sha256_file_hex(m.path) + "</span></p>\n";
    std::vector<std::vector<std::string>> rows;
    for (const auto& [name, value] : m.figures) rows.push_back({name, value});
    html += html_table({m.kind == "laser" ? "ISO 230-2" : "ISO 230-4", ""}, rows, false);
    if (!m.notes.empty()) {
      html += "<ul class=\"notes\">\n";
      for (const std::string& n : m.notes) html += "<li>" + escaped(n) + "</li>\n";
      html += "</ul>\n";
    }
    html += html_png_figure(pngs[k], m.title,
                            m.kind == "laser" ? "ISO 230-2: each run, the means up and down with their +-2s bands."
                                              : "ISO 230-4: the radius deviation of each direction, magnified.");
    html += "</div>\n";
  }
  for (const std::string& s : found.skipped) html += "<p class=\"note\">skipped: " + escaped(s) + "</p>\n";
  return html;
}

}  // namespace

Report accuracy_report(const machine::Model& model, const ReportOptions& options, std::ostream& progress) {
  const Drawings drawings;
  Report report;
  // Measurements first: a bad file stops the report before the long parts run.
  Measurements measured;
  std::vector<std::string> measurement_pngs;
  if (!options.measurements.empty()) {
    measured = read_measurements(options.measurements, model.info.name, [&](std::size_t k) {
      return drawings.path("measurement_" + std::to_string(k) + ".png");
    });
    for (const Measurement& m : measured.found) measurement_pngs.push_back(drawings.png(m.figure));
    progress << "  measurements: " << measured.found.size() << " read from " << options.measurements << ", "
             << measured.skipped.size() << " files skipped\n";
  }
  const std::vector<LabelledEvaluation> accepted = read_acceptance(options.acceptance);
  if (!accepted.empty()) progress << "  acceptance: " << acceptance_summary(accepted) << "\n";
  Page page;
  page.section("machine", "The machine", machine_section(model));
  page.section("tables", "Error tables", tables_section(model, drawings, report.figures, progress));
  page.section("location", "Location errors", location_section(model));
  Summary summary = {{"machine", model.info.name + " (" + shown_path(model.path) + ")"}};
  page.section("compensation", "Compensation types (ISO/TR 16907 Annex A)", compensation_section(model, summary));
  page.section("balance", "Accuracy balance", balance_section(model, drawings, report.figures, progress, summary));
  page.section("volume", "Volume map: the tool-tip error over the working volume",
               volume_section(model, options, drawings, report.figures, progress, summary));
  if (!options.measurements.empty()) {
    page.section("measurements", "Measurements", measurements_section(measured, measurement_pngs));
    report.figures += static_cast<int>(measured.found.size());
    report.measurements = static_cast<int>(measured.found.size());
    std::string titles;
    for (const Measurement& m : measured.found) titles += (titles.empty() ? "" : "; ") + m.title;
    summary.push_back(
        {"measurements (" + std::to_string(measured.found.size()) + ")", titles.empty() ? "none found" : titles});
  }
  if (!accepted.empty()) {
    page.section("acceptance", "Acceptance (ISO/TR 16907 11.3)",
                 acceptance_section(accepted, drawings, report.figures));
    report.acceptance = static_cast<int>(accepted.size());
    summary.push_back({"acceptance verdict (ISO/TR 16907 11.3)", acceptance_summary(accepted)});
  }
  const std::string header = "<p>Made " + utc_now() + " by <code>" + escaped(options.command) + "</code> from " +
                             escaped(shown_path(model.path)) + " (sha256 <span class=\"hash\">" +
                             sha256_file_hex(model.path) + "</span>).</p>\n<h2>Summary</h2>\n" +
                             html_table({}, summary, false) + "<h2>Contents</h2>\n";
  report.html = page.html("Accuracy report: " + model.info.name, header);
  report.sections = page.sections();
  return report;
}

}  // namespace vc::report
