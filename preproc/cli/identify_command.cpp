// `volcomp identify laser RUNS.csv --error EXX`: laser interferometer runs (ISO 230-2 test
// cycle) evaluated as ISO 230-2 does, suspicious runs left out with the reason, and the error
// table written in the project's CSV format with the measurement's metadata
// (preproc/identify/README.md).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <cctype>
#include <cstdlib>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

#include "vc/tables/atomic_file.hpp"
#include "commands.hpp"
#include "vc/tables/number_text.hpp"
#include "vc/identify/iso230_4.hpp"
#include "vc/identify/iso230_2.hpp"
#include "vc/identify/probe_log.hpp"
#include "vc/identify/rtest.hpp"
#include "vc/identify/sphere_centres.hpp"
#include "vc/identify/squareness_choice.hpp"
#include "vc/identify/laser_into_machine.hpp"
#include "vc/identify/laser_line.hpp"
#include "vc/identify/laser_runs.hpp"
#include "vc/identify/laser_table.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/plot/circle_plot.hpp"
#include "vc/plot/component_names.hpp"
#include "vc/plot/laser_plot.hpp"
#include "vc/tables/csv.hpp"
#include "vc/tables/source_error.hpp"
#include "vc/shop/machine_file_writer.hpp"
#include "vc/tables/symbols.hpp"

namespace vc::cli {
namespace {

struct IdentifyLaserArgs {
  std::string runs;                      // laser runs CSV
  std::string error;                     // the component error they measure: EXX, EYX, EAX, ECC, ...
  std::string output;                    // error table CSV (optional)
  std::string direction = "both";        // the table's value: both (mean bidirectional), up or down
  bool keep_all = false;                 // keep the suspicious runs in the evaluation
  std::string machine;                   // machine file whose axis takes the table (optional)
  std::string machine_out;               // folder: the table and a copy of the machine file using it
  std::string at;                        // where the axes stood, "x=0,y=-160,..." (default: the runs' "# at:")
  std::optional<double> tool_length_mm;  // the tool-side optic L below the gauge point (default: the runs')
  std::vector<double> tool_point_mm;     // ... or anywhere in the spindle frame, x,y,z from the gauge point
  std::string reference;                 // datum, least-squares, end-points, none (default by the error)
  std::string squareness;                // a straightness's slope goes into this location error (e.g. EC0X)
  std::string plot;  // the ISO 230-2 graph, .png or .svg (optional, gnuplot; its data: .csv beside it)
};

struct IdentifyCircleArgs {
  std::string run;                  // circular test CSV
  std::string plane;                // XY, YZ, ZX (default: the file's "# plane:")
  std::optional<double> radius_mm;  // default: the file's "# radius_mm:"
  std::string machine;              // to express the squareness in its terms (optional)
  std::string machine_out;          // folder for the machine file with the squareness set
  std::string symbol;               // which term takes it (default: the one the file uses)
  std::string plot;                 // the polar plot, .png or .svg (optional, gnuplot; its data: .csv beside it)
  std::optional<double> tool_length_mm;  // the ball's offset from the gauge point (default: "# tool_length_mm:")
  std::string centre;                    // the joints at the circle's centre (default: "# centre:")
};

struct IdentifySphereArgs {
  std::string machine;
  std::string centres;                   // CSV: the joints at the sphere's centre, one pose per row
  std::vector<std::string> deviations;   // location errors to identify (default: all of the rotary axes)
  std::optional<double> tool_length_mm;  // default: the machine file's
  std::string machine_out;               // folder for the machine file with the identified values
};

// Deviations in um (lengths) or arcsec and urad (angles), for the printout.
std::string shown(double v, tables::Quantity q) {
  return q == tables::Quantity::Length
             ? fixed_text(v * 1e3, 2) + " um"
             : fixed_text(v * 648000.0 / M_PI, 2) + " arcsec (" + fixed_text(v * 1e6, 1) + " urad)";
}

// A plot's image or its data CSV (the image's name with .csv) must not be one of the command's
// other files: `identify circle run.csv --plot run.png` would overwrite the run with the plot's data.
void refuse_plot_over(const std::string& image, const std::vector<std::string>& files) {
  namespace fs = std::filesystem;
  const auto same = [](const std::string& a, const std::string& b) {
    return fs::absolute(a).lexically_normal() == fs::absolute(b).lexically_normal();
  };
  for (const std::string& file : files)
    if (!file.empty() && (same(plot::data_path(image), file) || same(image, file)))
      throw std::runtime_error("--plot " + image + " writes " + (same(image, file) ? image : plot::data_path(image)) +
                               ", which is " + file + ", a file of this command: give the plot another name");
}

int run_identify_laser(const IdentifyLaserArgs& args, std::ostream& out) {
  const auto symbol = tables::parse_error_symbol(args.error);
  if (!symbol || symbol->location)
    throw std::runtime_error("--error " + args.error +
                             ": the component error the runs measure (EXX positioning, EYX "
                             "straightness, EAX angular, ECC a rotary axis's positioning ...)");
  if (args.direction != "both" && args.direction != "up" && args.direction != "down")
    throw std::runtime_error("--direction must be both, up or down");
  const identify::TableValue which = args.direction == "up"     ? identify::TableValue::Up
                                     : args.direction == "down" ? identify::TableValue::Down
                                                                : identify::TableValue::Bidirectional;
  if (!args.plot.empty()) refuse_plot_over(args.plot, {args.runs, args.output});
  const identify::LaserRuns runs = identify::read_laser_runs(args.runs);
  const bool rotary_axis = symbol->axis == 'A' || symbol->axis == 'B' || symbol->axis == 'C';
  if (runs.rotary != rotary_axis)
    throw std::runtime_error(args.runs + ": the targets are in " + (runs.rotary ? "deg" : "mm") + " but " + args.error +
                             " is an error of the " + (rotary_axis ? "rotary" : "linear") + " axis " +
                             std::string(1, symbol->axis));
  if (runs.quantity != symbol->quantity())
    throw std::runtime_error(args.runs + ": the deviations are " +
                             (runs.quantity == tables::Quantity::Length ? "lengths" : "angles") + " but " + args.error +
                             " is " +
                             (symbol->quantity() == tables::Quantity::Length ? "a translation" : "a rotation"));

  const std::vector<identify::SuspiciousRun> suspicious = identify::suspicious_runs(runs);
  std::set<identify::RunKey> left_out;
  for (const auto& s : suspicious)
    if (!args.keep_all) left_out.insert(s.run);
  const identify::Iso230_2 e = identify::evaluate_iso230_2(runs, left_out);
  const tables::Quantity q = runs.quantity;

  out << "volcomp identify laser: " << args.runs << ", " << args.error << ", " << e.targets.size() << " targets, "
      << e.runs_up << " runs up and " << e.runs_down << " down\n";
  for (const auto& [key, value] : runs.metadata) out << "  " << key << ": " << value << "\n";
  for (const auto& s : suspicious)
    out << "  " << (args.keep_all ? "suspicious (kept): " : "left out: ") << s.reason << "\n";
  // The figures, printed and (--plot) written on the graph: the same text.
  const auto up_down = [&](double up, double down) {
    return " (up " + shown(up, q) + ", down " + shown(down, q) + ")";
  };
  const std::vector<std::array<std::string, 3>> figures = {
      {"reversal value", "B", shown(e.reversal, q) + " (mean " + shown(e.mean_reversal, q) + ")"},
      {"repeatability", "R", shown(e.repeatability, q) + up_down(e.repeatability_up, e.repeatability_down)},
      {"systematic deviation", "E", shown(e.systematic, q) + up_down(e.systematic_up, e.systematic_down)},
      {"mean bidirectional range", "M", shown(e.range, q)},
      {"accuracy", "A", shown(e.accuracy, q) + up_down(e.accuracy_up, e.accuracy_down)}};
  out << "ISO 230-2 evaluation:\n";
  for (const auto& [name, letter, text] : figures) {
    std::string label = name + " " + letter;
    label.resize(std::max<std::size_t>(label.size() + 1, 28), ' ');
    out << "  " << label << text << "\n";
  }
  out << "  target " << (runs.rotary ? "[deg]" : "[mm]") << "   mean up   mean down   bidirectional   B_i   R_i  ("
      << (q == tables::Quantity::Length ? "um" : "urad") << ")\n";
  const double unit = q == tables::Quantity::Length ? 1e3 : 1e6;
  for (const identify::TargetStatistics& t : e.targets)
    out << "  " << number_text(t.target) << "  " << fixed_text(t.mean_up * unit, 3) << "  "
        << fixed_text(t.mean_down * unit, 3) << "  " << fixed_text(t.mean * unit, 3) << "  "
        << fixed_text(t.reversal * unit, 3) << "  " << fixed_text(t.r * unit, 3) << "\n";
  if (identify::spans_one_turn(e, runs.rotary))
    out << "One full turn: 0 and 360 deg are one position; the table holds their mean there (periodic), they read "
        << shown(e.targets.front().mean, q) << " and " << shown(e.targets.back().mean, q) << ".\n";
  out << "The table holds the "
      << (args.direction == "both" ? "mean bidirectional deviation" : args.direction + " runs' mean")
      << " at each target. The reversal (B = " << shown(e.reversal, q)
      << ") is not part of the geometric model: volkins leaves it (the drive's backlash compensation takes it)";
  if (std::string("XYZABC")[static_cast<std::size_t>(symbol->component)] == symbol->axis)  // positioning
    out << "; for a stock LinuxCNC, volcomp fit-tables --reversal " << symbol->axis << "=" << args.runs
        << " puts it into the COMP_FILE";
  out << ".\n";

  const std::vector<identify::TableRow> rows = identify::laser_table_rows(e, runs.rotary, which);
  std::vector<std::string> comments = {
      args.error + " identified by volcomp identify laser from " + args.runs +
      " (ISO 230-2: " + std::to_string(e.runs_up) + " runs up, " + std::to_string(e.runs_down) + " down" +
      (left_out.empty() ? "" : ", " + std::to_string(left_out.size()) + " left out") + ")"};
  for (const auto& [key, text] : runs.metadata) comments.push_back(key + ": " + text);
  comments.push_back(
      "value: " +
      (args.direction == "both" ? std::string("mean bidirectional deviation") : args.direction + " runs' mean") +
      "; reversal B " + shown(e.reversal, q) + ", repeatability R " + shown(e.repeatability, q) + ", accuracy A " +
      shown(e.accuracy, q));

  if (!args.machine_out.empty() && args.machine.empty())
    throw std::runtime_error("--machine-out needs --machine: the machine file whose axis takes the table");
  std::optional<machine::Model> model;
  int joint = -1;
  if (!args.machine.empty()) {
    model = machine::load_machine(args.machine);
    joint = model->joint_of(symbol->axis);
    if (joint < 0)
      throw std::runtime_error(args.error + " is an error of axis " + std::string(1, symbol->axis) + ", which " +
                               model->info.name + " (" + args.machine + ") does not have");
  }
  // Where the runs were made (--machine-out): the runs' metadata, or the options; read before
  // anything is written, so that a refusal leaves nothing behind.
  identify::LaserLineRuns line;
  std::string at;
  if (!args.machine_out.empty()) {
    const auto metadata = [&](const std::string& key) {
      for (const auto& [k, text] : runs.metadata)
        if (k == key) return text;
      return std::string();
    };
    line.setup.joint = joint;
    line.setup.error = *symbol;
    at = !args.at.empty() ? args.at : metadata("at");
    if (at.empty())
      throw std::runtime_error(args.runs + ": where did the axes stand during the runs? Add a '# at: " + [&] {
        std::string example;
        for (int j = 0; j < model->joint_count(); ++j)
          example += std::string(j ? ", " : "") +
                     static_cast<char>(std::tolower(model->axes[static_cast<std::size_t>(j)].letter)) + "=...";
        return example;
      }() + "' line or give --at: the laser reads the machine's errors there too");
    try {
      line.setup.at = identify::parse_axis_positions(*model, joint, at);
    } catch (const std::exception& bad) {
      throw std::runtime_error((!args.at.empty() ? std::string("--at: ") : args.runs + ": '# at:': ") + bad.what());
    }
    const auto vector3 = [&](const std::string& text, const std::string& what) {
      std::vector<double> v;
      std::stringstream list(text);
      for (std::string item; std::getline(list, item, ',');) {
        std::size_t used = 0;
        try {
          v.push_back(std::stod(item, &used));
        } catch (const std::exception&) {
          used = 0;
        }
        if (used == 0 || item.find_first_not_of(" \t", used) != std::string::npos)
          throw std::runtime_error(what + ": '" + item + "' is not a number (mm)");
      }
      if (v.size() != 3) throw std::runtime_error(what + ": three numbers, x, y, z (mm)");
      return Eigen::Vector3d(v[0], v[1], v[2]);
    };
    if (!args.tool_point_mm.empty())
      line.setup.tool_point_mm = Eigen::Vector3d(args.tool_point_mm[0], args.tool_point_mm[1], args.tool_point_mm[2]);
    else if (args.tool_length_mm)
      line.setup.tool_point_mm = Eigen::Vector3d(0, 0, -*args.tool_length_mm);
    else if (!metadata("tool_point_mm").empty())
      line.setup.tool_point_mm = vector3(metadata("tool_point_mm"), args.runs + ": '# tool_point_mm:'");
    else if (!metadata("tool_length_mm").empty())
      line.setup.tool_point_mm =
          Eigen::Vector3d(0, 0, -vector3(metadata("tool_length_mm") + ",0,0", args.runs + ": '# tool_length_mm:'").x());
    else
      throw std::runtime_error(
          args.runs +
          ": where was the tool-side optic? Add a '# tool_length_mm: L' line (the optic L "
          "below the spindle gauge point, on its axis) or '# tool_point_mm: x, y, z' (in the spindle "
          "frame), or give --tool-length / --tool-point");
    if (!metadata("measured_at_mm").empty())
      throw std::runtime_error(
          args.runs +
          ": '# measured_at_mm:' says where the optics sat relative to the axis's pole; "
          "with --machine-out give where the tool-side optic sat instead ('# tool_point_mm: x, y, z' in "
          "the spindle frame from its gauge point): the solve reads the Abbe terms from there");
    line.reference = args.reference.empty()              ? identify::default_reference(*symbol, runs.rotary)
                     : args.reference == "datum"         ? identify::Reference::Datum
                     : args.reference == "least-squares" ? identify::Reference::LeastSquares
                     : args.reference == "end-points"    ? identify::Reference::EndPoints
                                                         : identify::Reference::None;
    for (const identify::TargetStatistics& t : e.targets) {
      line.targets.push_back(t.target);
      line.readings.push_back(identify::table_value(t, which));
      line.noise.push_back(identify::table_value_uncertainty(t, e, which));
    }
    line.squareness = args.squareness;
    line.comments = comments;
  }
  // The graph before any other output: a failing gnuplot leaves nothing written.
  if (!args.plot.empty()) {
    plot::LaserPlotText text;
    text.title = "ISO 230-2: " + args.error + " " + plot::component_meaning(*symbol) + " of axis " +
                 std::string(1, symbol->axis) + (model ? ", " + model->info.name : std::string());
    for (const auto& [key, note] : runs.metadata) text.notes.push_back(key + ": " + note);
    for (const auto& s : suspicious)
      text.notes.push_back((args.keep_all ? "suspicious (kept): " : "left out (not drawn): ") + s.reason);
    for (const auto& [name, figure_symbol, figure_text] : figures)
      text.figures.emplace_back(figure_symbol, figure_text);
    plot::draw(plot::laser_plot(runs, left_out, e, text, args.plot));
    out << "plot written: " << args.plot << " (its data: " << plot::data_path(args.plot) << ")\n";
  }

  // The readings' table (-o) after the machine file: a refused identification leaves neither.
  const auto write_readings = [&] {
    if (!args.output.empty()) {
      tables::write_atomically(args.output, [&](std::ostream& csv) {
        for (const std::string& c : comments) csv << "# " << c << "\n";
        csv << "# the readings: the tool against the part, as the instrument read them (error = actual - nominal)\n";
        csv << static_cast<char>(std::tolower(symbol->axis)) << (runs.rotary ? "[deg]" : "[mm]") << "," << args.error
            << (q == tables::Quantity::Length ? "[um]" : "[urad]") << "\n";
        for (const auto& [target, v] : rows) csv << number_text(target) << "," << fixed_text(v * unit, 4) << "\n";
      });
      out << "table written: " << args.output << " (the readings: the tool against the part)";
      if (args.machine_out.empty())
        out << ". Into a machine file: --machine M.toml --machine-out DIR, which solves for what the file holds (the "
            << "axis's chain and direction, the other errors on the line)";
      out << "\n";
    }
  };
  if (args.machine_out.empty()) {
    write_readings();
    return 0;
  }
  const identify::LaserIntoMachine r =
      identify::laser_into_machine(*model, line, args.machine_out, "volcomp identify laser from " + args.runs);

  const auto in_unit = [&](double v) {
    return fixed_text(v * unit, 3) + (q == tables::Quantity::Length ? " um" : " urad");
  };
  const auto per = [&](double slope) {  // um/m or urad/m (linear axes), per deg (rotary)
    return fixed_text(slope * unit * (runs.rotary ? 1.0 : 1e3), 3) + (q == tables::Quantity::Length ? " um" : " urad") +
           (runs.rotary ? "/deg" : "/m");
  };
  out << "Into " << args.machine << " (" << model->info.name << "): the runs at " << at << ", the tool-side optic at "
      << number_text(line.setup.tool_point_mm.x()) << ", " << number_text(line.setup.tool_point_mm.y()) << ", "
      << number_text(line.setup.tool_point_mm.z()) << " mm in the spindle frame; " << symbol->axis << "'s "
      << (model->axes[static_cast<std::size_t>(joint)].chain == machine::Chain::Tool ? "tool" : "workpiece")
      << " chain, the file's other errors as they are\n";
  const auto arcsec = [](double rad) { return fixed_text(rad * 648000.0 / M_PI, 3) + " arcsec"; };
  switch (line.reference) {
    case identify::Reference::None:
      out << "  reference none: the readings as they are\n";
      break;
    case identify::Reference::Datum:
      out << "  reference datum: the runs read " << in_unit(r.runs_reference.offset) << " at "
          << number_text(line.targets.front()) << (runs.rotary ? " deg" : " mm") << " (the laser's zero), the file "
          << in_unit(r.file_reference.offset) << ": the file keeps its origin\n";
      break;
    default:
      out << "  reference " << identify::reference_name(line.reference) << " (ISO 230-1): the runs' line "
          << in_unit(r.runs_reference.offset) << " + " << per(r.runs_reference.slope);
      if (!r.squareness.empty())
        out << "; the table holds the straightness about its line, the slope is a squareness: " << r.squareness << " = "
            << arcsec(r.squareness_rad) << " (was " << arcsec(r.squareness_before_rad)
            << "; one value in the file: identify circle and sphere set the same one)\n";
      else
        out << "; " << symbol->axis
            << " carries the part, so no squareness turns its line against it: the slope is the "
            << "optics' alignment, replaced by the file's " << per(r.file_reference.slope)
            << " (--reference none keeps the runs' slope, for optics aligned to the part)\n";
  }
  for (const std::string& kept : r.kept)
    out << "  " << args.error << " of " << kept << " kept: the solve read it where the runs stood\n";
  const auto [low, high] = std::minmax_element(r.table.begin(), r.table.end());
  out << "  " << r.table_file << ": " << args.error << " " << in_unit(*low) << " .. " << in_unit(*high)
      << " (the axis's own motion, in its frame)\n"
      << "  self-check: the written file reads the runs within " << in_unit(r.largest_misfit) << "\n"
      << "machine file written: " << r.written << " (axis " << symbol->axis << ": " << args.error << " from "
      << r.table_file;
  if (!r.zeroed_copy.empty())
    out << "; in " << r.zeroed_copy << ", the copy of the table that held it, " << args.error << " is zero";
  out << ")\n";
  write_readings();
  return 0;
}

// Where the circle ran and the ball's offset (identify::CircleSetup): the options, else the
// run file's "# centre:" and "# tool_length_mm:", else the middle of the travel and the machine
// file's tool length, said so (the standard wants the offset declared).
identify::CircleSetup circle_setup(const IdentifyCircleArgs& args, const identify::CircularTest& test,
                                   const machine::Model& model, std::ostream& out) {
  identify::CircleSetup setup = identify::default_circle_setup(model);
  const auto metadata = [&](const std::string& key) -> const std::string* {
    for (const auto& [k, v] : test.metadata)
      if (k == key) return &v;
    return nullptr;
  };
  std::string length_from = "--tool-length", centre_from = "--centre";
  if (args.tool_length_mm) {
    setup.tool_length_mm = *args.tool_length_mm;
  } else if (const std::string* v = metadata("tool_length_mm")) {
    char* end = nullptr;
    setup.tool_length_mm = std::strtod(v->c_str(), &end);
    if (v->empty() || *end != '\0' || !std::isfinite(setup.tool_length_mm))
      throw std::runtime_error(test.path + ": '# tool_length_mm: " + *v + "' is not a length in mm");
    length_from = "the run's '# tool_length_mm:'";
  } else {
    length_from = "not declared: the machine file's tool_length_mm";
  }
  const std::string* centre_text = args.centre.empty() ? metadata("centre") : &args.centre;
  if (centre_text) {
    try {
      setup.centre = identify::parse_axis_positions(model, -1, *centre_text);
    } catch (const std::exception& e) {
      throw std::runtime_error((args.centre.empty() ? test.path + ": '# centre:'" : std::string("--centre")) + ": " +
                               e.what());
    }
    if (args.centre.empty()) centre_from = "the run's '# centre:'";
  } else {
    centre_from = "not given: the middle of the travel";
  }
  std::string at;
  for (int j = 0; j < model.joint_count(); ++j)
    at += std::string(j ? ", " : "") +
          static_cast<char>(std::tolower(static_cast<unsigned char>(model.axes[static_cast<std::size_t>(j)].letter))) +
          "=" + number_text(setup.centre[j]);
  out << "the circle simulated on the file about " << at << " (" << centre_from << "), the ball "
      << number_text(setup.tool_length_mm) << " mm from the gauge point (" << length_from << ")\n";
  if (length_from.rfind("not declared", 0) == 0)
    out << "  note: declare the tool-side ball's offset (--tool-length, the active tool length when the circle "
           "ran): an angular error moves the ball by its Abbe arm, so the file's share of the squareness depends on "
           "it (ISO/TR 16907 asks for it wherever L-ANG, R-ANG, L-VOL or R-VOL is on)\n";
  return setup;
}

int run_identify_circle(const IdentifyCircleArgs& args, std::ostream& out) {
  if (!args.plot.empty()) refuse_plot_over(args.plot, {args.run});
  identify::CircularTest test = identify::read_circular_test(args.run);
  if (!args.plane.empty()) test.plane = args.plane;
  if (args.radius_mm) test.radius_mm = *args.radius_mm;
  const identify::CircularEvaluation e = identify::evaluate_circular_test(test);
  const auto um = [](double mm) { return fixed_text(mm * 1e3, 2) + " um"; };
  const auto arcsec = [](double rad) { return fixed_text(rad * 648000.0 / M_PI, 2) + " arcsec"; };
  const std::string first(1, test.plane[0]), second(1, test.plane[1]);
  out << "volcomp identify circle: " << args.run << ", plane " << test.plane << ", radius "
      << number_text(test.radius_mm) << " mm\n";
  for (const auto& [key, value] : test.metadata) out << "  " << key << ": " << value << "\n";
  // Each figure's text once: printed (joined as before) and, with --plot, written on the plot.
  const std::string both = "bidirectional circular deviation G(b) " + um(e.circular_deviation_mm);
  const std::string hysteresis = "circular hysteresis H " + um(e.hysteresis_mm);
  std::vector<std::string> plotted = {both};
  if (test.runs.size() == 2) plotted.push_back(hysteresis);
  out << "ISO 230-4:\n  " << both << (test.runs.size() == 2 ? ", " + hysteresis : std::string()) << "\n";
  for (const identify::CircleFit& f : e.fits) {
    const std::string deviation = "circular deviation G " + um(f.circular_deviation_mm),
                      radial = "radial deviation F " + um(f.radial_deviation_mm),
                      centre = "centre offset " + first + " " + um(f.centre_first_mm) + ", " + second + " " +
                               um(f.centre_second_mm),
                      square = "squareness " + arcsec(f.squareness_rad) + ", scale mismatch " +
                               fixed_text(f.scale_mismatch * 1e6, 2) + " um/m",
                      residual = "left by the first-order fit RMS " + um(f.residual_rms_mm);
    std::string spikes = "reversal spikes:";
    std::vector<std::string> spike_texts;
    for (const auto& [angle, height] : f.spikes) {
      spike_texts.push_back(number_text(angle) + " deg " + um(height));
      spikes += " " + spike_texts.back();
    }
    out << "  " << (f.ccw ? "ccw" : "cw ") << ": " << deviation << ", " << radial << "; " << centre << "; " << square
        << "; " << residual << "\n    " << spikes << "\n";
    plotted.push_back(std::string(f.ccw ? "ccw" : "cw") + ":");
    for (const std::string& line : {deviation, radial, centre, square, residual}) plotted.push_back("   " + line);
    plotted.push_back("   reversal spikes:");  // two a line: the plot's column is narrower than the printout
    for (std::size_t k = 0; k < spike_texts.size(); k += 2)
      plotted.push_back("      " + spike_texts[k] + (k + 1 < spike_texts.size() ? ",  " + spike_texts[k + 1] : ""));
  }
  const std::string theta = "theta = " + arcsec(e.squareness_rad),
                    mismatch = "scale mismatch e" + first + " - e" + second + " = " +
                               fixed_text(e.scale_mismatch * 1e6, 2) + " um/m";
  out << "squareness (both directions' mean; " << first << "' = " << first << " + theta " << second << "): " << theta
      << "; " << mismatch << " (a positioning table's slope: measure it with the laser)\n";
  plotted.push_back("squareness (both directions' mean): " + theta);
  plotted.push_back(mismatch);
  std::optional<machine::Model> model;
  if (!args.machine.empty()) model = machine::load_machine(args.machine);
  if (!args.plot.empty()) {
    plot::CirclePlotText text;
    text.title = "Circular test (ISO 230-4), plane " + test.plane + ", radius " + number_text(test.radius_mm) + " mm" +
                 (model ? ", " + model->info.name : std::string());
    std::string metadata;
    for (const auto& [key, value] : test.metadata)
      if (key != "plane" && key != "radius_mm") metadata += (metadata.empty() ? "" : "; ") + key + ": " + value;
    if (!metadata.empty()) text.notes.push_back(metadata);
    text.figures = plotted;
    plot::draw(plot::circle_plot(test, text, args.plot));
    out << "plot written: " << args.plot << " (its data: " << plot::data_path(args.plot) << ")\n";
  }
  if (!model) return 0;
  const identify::CircleSetup setup = circle_setup(args, test, *model, out);
  const std::vector<identify::SquarenessTerm> terms =
      identify::squareness_terms(*model, test.plane, test.radius_mm, e.squareness_rad, setup);
  out << "in " << args.machine
      << "'s terms (measured with the compensation off: the machine's own squareness): the file "
      << "shows " << arcsec(terms.empty() ? 0.0 : terms.front().file_squareness_rad)
      << " now (its lines and its tables' "
      << "slopes); for the measured one, with its other errors as they are:\n";
  for (const auto& t : terms)
    out << "  " << t.symbol << " = " << arcsec(t.value_rad) << " (the file has " << arcsec(t.in_file_rad) << ")\n";
  if (args.machine_out.empty()) return 0;
  const identify::SquarenessTerm* chosen = identify::chosen_squareness_term(terms, args.symbol);
  if (!chosen)
    throw std::runtime_error("--symbol " + args.symbol + " is not one of the squareness terms of the " + test.plane +
                             " plane");
  const auto s = tables::parse_error_symbol(chosen->symbol);
  const std::string written =
      shop::write_machine_with_tables(*model, args.machine_out, {}, "volcomp identify circle from " + args.run,
                                      {{model->joint_of(s->axis), s->component, chosen->value_rad}});
  // The self-check: the written file shows the measured squareness.
  const std::vector<identify::SquarenessTerm> after =
      identify::squareness_terms(machine::load_machine(written), test.plane, test.radius_mm, e.squareness_rad, setup);
  if (after.empty() || std::abs(after.front().file_squareness_rad - e.squareness_rad) > 0.005 * M_PI / 648000) {
    std::filesystem::remove(written);
    throw std::runtime_error("the written file shows a squareness of " +
                             arcsec(after.empty() ? 0.0 : after.front().file_squareness_rad) +
                             " where the circle measured " + arcsec(e.squareness_rad) + ": nothing written");
  }
  out << "machine file written: " << written << " (" << chosen->symbol << " = " << arcsec(chosen->value_rad)
      << "; it shows " << arcsec(after.front().file_squareness_rad) << ")\n";
  return 0;
}

int report_location_fit(const machine::Model& model, const std::vector<identify::SpherePose>& poses,
                        const IdentifySphereArgs& args, double length, const std::string& command, std::ostream& out);

int run_identify_sphere(const IdentifySphereArgs& args, std::ostream& out) {
  const machine::Model model = machine::load_machine(args.machine);
  // A probe-plan log (its '# volcomp probe log' header) or a CSV of centres.
  std::string first;
  {
    std::ifstream in(args.centres);
    if (!in) throw LoadError({args.centres}, "cannot open the probe log or centres");
    while (std::getline(in, first) && first.find_first_not_of(" \t\r") == std::string::npos) {
    }
  }
  std::vector<identify::SpherePose> poses;
  double length = args.tool_length_mm.value_or(model.tool_length_mm);
  if (first.rfind("# volcomp probe log", 0) == 0 || first.rfind("POINT", 0) == 0) {
    const identify::ProbeLog log = identify::read_probe_log(args.centres, model);
    poses = log.centres;
    if (!args.tool_length_mm && log.probe_length_mm > 0) length = log.probe_length_mm;
    out << "probe log: " << poses.size() << " poses, sphere " << number_text(log.sphere_diameter_mm) << " mm, ball "
        << number_text(log.ball_diameter_mm) << " mm; the points lie within " << fixed_text(log.largest_residual_um, 2)
        << " um of their fitted spheres\n";
  } else {
    poses = identify::read_sphere_centres(args.centres, model);
  }
  return report_location_fit(model, poses, args, length, "sphere", out);
}

// The R-test's readings as the sphere's centres (rtest.hpp), then the same fit.
int run_identify_rtest(const IdentifySphereArgs& args, std::ostream& out) {
  const machine::Model model = machine::load_machine(args.machine);
  const double length = args.tool_length_mm.value_or(model.tool_length_mm);
  const std::vector<identify::RTestReading> readings = identify::read_rtest_readings(args.centres, model);
  double largest = 0.0;
  for (const identify::RTestReading& r : readings) largest = std::max(largest, r.deviation_mm.norm());
  out << "R-test readings: " << readings.size() << " poses, the sphere's centre up to " << fixed_text(largest * 1e3, 2)
      << " um from the nest's; the nest " << number_text(length) << " mm from the gauge point\n";
  return report_location_fit(model, identify::rtest_centres(model, readings, length), args, length, "rtest", out);
}

// The location errors fitted to the sphere's centres, printed, and written with --machine-out.
int report_location_fit(const machine::Model& model, const std::vector<identify::SpherePose>& poses,
                        const IdentifySphereArgs& args, double length, const std::string& command, std::ostream& out) {
  const identify::SphereFit fit = identify::identify_from_sphere(model, poses, args.deviations, length);
  const auto value = [](int component, double v) {
    return component < 3 ? fixed_text(v * 1e3, 2) + " um" : fixed_text(v * 648000.0 / M_PI, 2) + " arcsec";
  };
  out << "volcomp identify " << command << ": " << args.centres << ", " << poses.size() << " poses, " << model.info.name
      << " at L = " << number_text(length) << " mm (the linear axes' errors enter the centres: identify after the "
      << "linear tables are in the machine file)\n"
      << "  " << fit.rank << " of " << fit.parameters << " location errors identified, condition "
      << fixed_text(fit.condition, 1) << "; sphere centre in the part frame " << fixed_text(fit.centre_mm.x(), 4)
      << ", " << fixed_text(fit.centre_mm.y(), 4) << ", " << fixed_text(fit.centre_mm.z(), 4) << " mm\n";
  for (const identify::LocationEstimate& e : fit.estimates)
    out << "  " << e.symbol << " = " << value(e.component, e.value) << " +- " << value(e.component, e.uncertainty)
        << " (standard uncertainty; the file has " << value(e.component, e.before) << ")\n";
  for (const identify::NotSeparable& n : fit.not_separable) {
    out << "  " << n.symbol << ": not separable from";
    for (const std::string& w : n.with) out << " " << w;
    out << " with these poses: left as it is; only their combination is seen, carried by the others\n";
  }
  out << "  distance of the model's tip from the common centre per pose, um (before -> after):";
  for (std::size_t k = 0; k < poses.size(); ++k)
    out << (k % 6 ? " " : "\n   ") << "line " << poses[k].line << ": " << fixed_text(fit.residual_before_um[k], 2)
        << " -> " << fixed_text(fit.residual_after_um[k], 2);
  out << "\n  RMS " << fixed_text(fit.rms_before_um, 3) << " -> " << fixed_text(fit.rms_after_um, 3) << " um\n";
  if (args.machine_out.empty()) return 0;
  std::vector<shop::LocationValue> values;
  for (const identify::LocationEstimate& e : fit.estimates)
    values.push_back({e.joint, e.component, e.value, e.uncertainty});
  const std::string written = shop::write_machine_with_tables(model, args.machine_out, {},
                                                              "volcomp identify " + command + " from " + args.centres,
                                                              values);
  machine::load_machine(written);  // it loads
  out << "machine file written: " << written << "\n";
  return 0;
}

void add_laser_command(CLI::App* identify, int& exit_code) {
  auto args = std::make_shared<IdentifyLaserArgs>();
  CLI::App* cmd = identify->add_subcommand(
      "laser", "Laser interferometer runs (ISO 230-2): evaluation, suspicious runs, the error table");
  cmd->add_option("RUNS", args->runs,
                  "runs CSV: target[mm],run,direction,deviation[um] or target[mm],1+[um],1-[um],...")
      ->required();
  cmd->add_option("--error", args->error, "the component error the runs measure: EXX, EYX, EAX, ECC, ...")->required();
  cmd->add_option("-o,--output", args->output, "error table CSV in the project's format");
  cmd->add_option("--direction", args->direction, "the table's value: both (mean bidirectional), up or down")
      ->capture_default_str();
  cmd->add_flag("--keep-all", args->keep_all, "keep the suspicious runs in the evaluation");
  cmd->add_option("--machine", args->machine, "machine file whose axis takes the identified table");
  cmd->add_option("--machine-out", args->machine_out,
                  "folder: the table and a copy of the machine file with it in place of the error's old values");
  cmd->add_option(
      "--at", args->at,
      "where every axis stood during the runs, e.g. x=0,y=-160,z=-150,b=0,c=0 (default: the runs' '# at:')");
  cmd->add_option("--tool-length", args->tool_length_mm,
                  "the tool-side optic's distance below the spindle gauge point, mm (default: the runs' "
                  "'# tool_length_mm:')");
  cmd->add_option("--tool-point", args->tool_point_mm,
                  "the tool-side optic in the spindle frame from the gauge point, X,Y,Z mm (the runs' "
                  "'# tool_point_mm:'); a tool's tip L long is 0,0,-L")
      ->delimiter(',')
      ->expected(3);
  cmd->add_option("--reference", args->reference,
                  "none: the readings as they are (positioning, angular: the default); datum: the laser zeroed "
                  "at the first target, the file keeps its value there; least-squares (a straightness's default) "
                  "or end-points: the straightness about that line, its slope a squareness")
      ->check(CLI::IsMember({"datum", "least-squares", "end-points", "none"}));
  cmd->add_option("--squareness", args->squareness,
                  "the location error that takes a straightness's slope, e.g. EC0X or EC0Y for EYX (default: the "
                  "one the file uses, else the measured axis's own)");
  cmd->add_option("--plot", args->plot,
                  "the ISO 230-2 graph, .png or .svg (gnuplot); the data it draws goes to a .csv beside it");
  cmd->callback([args, &exit_code] { exit_code = run_identify_laser(*args, std::cout); });
}

void add_circle_command(CLI::App* identify, int& exit_code) {
  auto args = std::make_shared<IdentifyCircleArgs>();
  CLI::App* cmd = identify->add_subcommand(
      "circle", "Circular test / ballbar (ISO 230-4): G, H, centre, squareness, scale mismatch, reversal spikes");
  cmd->add_option("RUN", args->run, "CSV: angle[deg],direction,deviation[um] or angle[deg],ccw[um],cw[um]")->required();
  cmd->add_option("--plane", args->plane, "XY, YZ or ZX (default: the file's '# plane:')");
  cmd->add_option("--radius", args->radius_mm, "the circle's radius, mm (default: the file's '# radius_mm:')");
  cmd->add_option("--machine", args->machine, "machine file: the squareness in its location errors");
  cmd->add_option("--machine-out", args->machine_out, "folder: a copy of the machine file with the squareness set");
  cmd->add_option("--symbol", args->symbol, "the location error that takes it (default: the one the file uses)");
  cmd->add_option("--tool-length", args->tool_length_mm,
                  "mm: the tool-side ball's offset from the spindle's gauge point, the active tool length while the "
                  "circle ran (default: the file's '# tool_length_mm:', else the machine file's tool length)");
  cmd->add_option("--centre", args->centre,
                  "the joints at the circle's centre, e.g. \"x=0, y=0, z=-200\" (default: the file's '# centre:', else "
                  "the middle of the travel, rotary axes at 0)");
  cmd->add_option("--plot", args->plot,
                  "the ballbar polar plot, .png or .svg (gnuplot); the data it draws goes to a .csv beside it");
  cmd->callback([args, &exit_code] { exit_code = run_identify_circle(*args, std::cout); });
}

void add_sphere_command(CLI::App* identify, int& exit_code) {
  auto args = std::make_shared<IdentifySphereArgs>();
  CLI::App* cmd = identify->add_subcommand(
      "sphere", "Rotary axes' location errors from a sphere's centre probed at several rotary positions");
  cmd->add_option("MACHINE", args->machine, "machine description file (.toml)")->required();
  cmd->add_option("CENTRES", args->centres,
                  "probe-plan log, or a CSV of the joints at the sphere's centre per pose (x,y,z,b,c)")
      ->required();
  cmd->add_option("--deviations", args->deviations, "location errors to identify, e.g. EX0C,EA0B (default: all)")
      ->delimiter(',');
  cmd->add_option("--tool-length", args->tool_length_mm, "probe length L, mm (default: the machine file's)");
  cmd->add_option("--machine-out", args->machine_out, "folder: a copy of the machine file with the values");
  cmd->callback([args, &exit_code] { exit_code = run_identify_sphere(*args, std::cout); });
}

void add_rtest_command(CLI::App* identify, int& exit_code) {
  auto args = std::make_shared<IdentifySphereArgs>();
  CLI::App* cmd = identify->add_subcommand(
      "rtest", "Rotary axes' location errors from an R-test (a sphere on the table, three sensors in the spindle)");
  cmd->add_option("MACHINE", args->machine, "machine description file (.toml)")->required();
  cmd->add_option("READINGS", args->centres,
                  "CSV: the commanded joints (x,y,z,b,c) and the sphere's centre against the nest's, "
                  "dx[um],dy[um],dz[um] in the spindle frame, one pose per row")
      ->required();
  cmd->add_option("--deviations", args->deviations, "location errors to identify, e.g. EX0C,EA0B (default: all)")
      ->delimiter(',');
  cmd->add_option("--tool-length", args->tool_length_mm,
                  "the nest's centre from the gauge point, mm (default: the machine file's tool length)");
  cmd->add_option("--machine-out", args->machine_out, "folder: a copy of the machine file with the values");
  cmd->callback([args, &exit_code] { exit_code = run_identify_rtest(*args, std::cout); });
}

}  // namespace

void add_identify_commands(CLI::App& volcomp, int& exit_code) {
  CLI::App* identify =
      volcomp.add_subcommand("identify", "From measurements to the machine file")->require_subcommand(1);
  add_laser_command(identify, exit_code);
  add_circle_command(identify, exit_code);
  add_sphere_command(identify, exit_code);
  add_rtest_command(identify, exit_code);
}

}  // namespace vc::cli
