#include "vc/identify/laser_into_machine.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>

#include "vc/machine/load_machine.hpp"
#include "vc/shop/machine_file_writer.hpp"
#include "vc/tables/csv.hpp"
#include "vc/tables/number_text.hpp"

namespace vc::identify {
namespace {

namespace fs = std::filesystem;

// The text of a table file with one column's cells 0, everything else as it is (comments,
// units, digits), `comment` first.
std::string zeroed_copy(const tables::ErrorTable& table, int column, const std::string& comment) {
  const SourceLocation& header = table.columns()[static_cast<std::size_t>(column)].where;
  std::ifstream in(table.path());
  if (!in) throw std::runtime_error("cannot read " + table.path());
  std::string text = "# " + comment + "\n";
  int cell = -1;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::vector<tables::CsvCell> cells = tables::split_csv_line(line);
    if (number == header.line) {
      for (std::size_t k = 0; k < cells.size(); ++k)
        if (cells[k].column == header.column) cell = static_cast<int>(k);
    } else if (number > header.line && cell >= 0 && static_cast<int>(cells.size()) > cell &&
               line.find_first_not_of(" \t\r") != std::string::npos && line[line.find_first_not_of(" \t")] != '#') {
      const std::size_t begin = static_cast<std::size_t>(cells[static_cast<std::size_t>(cell)].column) - 1;
      const std::size_t end = std::min(line.find(',', begin), line.find_last_not_of("\r \t") + 1);
      line = line.substr(0, begin) + "0" + line.substr(end);
    }
    text += line + "\n";
  }
  if (cell < 0) throw std::runtime_error(header.to_string() + ": cannot find this column again");
  return text;
}

bool over_own_position(const tables::ErrorTable& table, char axis) {
  return table.grid().size() == 1 && !table.grid()[0].is_temperature() && table.grid()[0].axis == axis;
}

// The identified table in place of the error's old values on the axis: the axis's 1-D table over
// its own position that holds the error is copied (under its own file name, so that its entry in
// the machine file, with its interpolation, scale and measured_at_mm, points at the copy) with
// that column zero, and the identified table is listed beside it (an axis's tables add up). The
// error's other tables (over other axes or a temperature) stay: the solve reads them where the
// runs stood. Two 1-D tables holding it are refused: which one the runs replace is the user's call.
std::vector<shop::ExtraTable> replacing_tables(const machine::Model& model, const LaserSetup& setup,
                                               shop::ExtraTable identified, LaserIntoMachine& result) {
  std::vector<shop::ExtraTable> extras;
  const tables::ErrorSymbol& symbol = setup.error;
  const tables::ErrorTable* holder = nullptr;
  int column = -1;
  for (const int t : model.axes[static_cast<std::size_t>(setup.joint)].tables) {
    const tables::ErrorTable& table = model.tables[static_cast<std::size_t>(t)].table;
    for (std::size_t c = 0; c < table.columns().size(); ++c) {
      if (table.columns()[c].symbol.name() != symbol.name()) continue;
      if (!over_own_position(table, symbol.axis)) {
        result.kept.push_back(table.path());
        continue;
      }
      if (holder)
        throw std::runtime_error(symbol.name() + " is in two tables over " +
                                 std::string(1, static_cast<char>(std::tolower(symbol.axis))) + " alone (" +
                                 holder->path() + ", " + table.path() + "): their sum is what the runs measured; " +
                                 "leave it in one of them");
      holder = &table;
      column = static_cast<int>(c);
    }
  }
  if (holder && fs::path(holder->path()).filename().string() != identified.file_name) {
    result.zeroed_copy = fs::path(holder->path()).filename().string();
    extras.push_back({setup.joint,
                      result.zeroed_copy,
                      *holder,
                      {},
                      zeroed_copy(*holder, column,
                                  "a copy of " + holder->path() + " with " + symbol.name() +
                                      " zero: " + identified.file_name + " holds it (volcomp identify laser)")});
  }
  extras.push_back(std::move(identified));
  return extras;
}

int table_index(const machine::Model& model, int joint, const std::string& file_name) {
  for (const int t : model.axes[static_cast<std::size_t>(joint)].tables)
    if (fs::path(model.tables[static_cast<std::size_t>(t)].table.path()).filename() == file_name) return t;
  throw std::runtime_error("the written machine file does not list " + file_name);
}

std::vector<double> readings(const machine::Model& model, const LaserLineRuns& runs) {
  std::vector<double> out;
  for (const double t : runs.targets) out.push_back(laser_reading(model, runs.setup, t));
  return out;
}

// A straightness's slope is a squareness: the location errors that turn the measured line against
// the part about the third direction (EYX: EC0X of X's line, or EC0Y of Y's), those of them that
// this machine's chains let do it (on a bed mill Y carries X and the part: EC0Y turns both alike).
// The requested one, else the one the file already uses (the measured axis's own first), else
// the measured axis's own; none where the measured axis carries the part (its line turns the part
// with it: the slope is then the optics' alignment against the part, which the file keeps).
std::optional<tables::ErrorSymbol> squareness_term(const machine::Model& model, const LaserLineRuns& runs) {
  const LaserSetup& setup = runs.setup;
  const int moving = static_cast<int>(std::string("XYZ").find(setup.error.axis)), reading = setup.error.component;
  const int about = 3 - moving - reading;
  std::vector<tables::ErrorSymbol> candidates;
  std::string names;
  for (const char letter : {setup.error.axis, "XYZ"[reading]}) {
    const int joint = model.joint_of(letter);
    if (joint < 0) continue;
    const tables::ErrorSymbol symbol{about + 3, letter, true};
    machine::Model tilted = model;
    const double before = model.axes[static_cast<std::size_t>(joint)].location_rad[about];
    set_location_rotation(tilted, joint, about + 3, before + 1e-5);
    const double change = reference_line(runs.targets, readings(tilted, runs), Reference::LeastSquares).slope -
                          reference_line(runs.targets, readings(model, runs), Reference::LeastSquares).slope;
    if (std::abs(change / 1e-5) < 0.1) continue;  // it does not turn this line against the part
    candidates.push_back(symbol);
    names += (names.empty() ? "" : " or ") + symbol.name();
  }
  if (candidates.empty() && !runs.squareness.empty())
    throw std::runtime_error("--squareness " + runs.squareness + ": no location error of this machine turns " +
                             std::string(1, setup.error.axis) + "'s line against the part in " + "XYZ"[reading] +
                             " (the axis carries the part)");
  if (candidates.empty()) return std::nullopt;
  if (!runs.squareness.empty()) {
    for (const auto& c : candidates)
      if (c.name() == runs.squareness) return c;
    throw std::runtime_error("--squareness " + runs.squareness + ": the slope of " + setup.error.name() +
                             " is a squareness of " + names + " on this machine");
  }
  for (const auto& c : candidates)
    if (model.axes[static_cast<std::size_t>(model.joint_of(c.axis))].location_rad[about] != 0.0) return c;
  return candidates.front();
}

}  // namespace

LaserIntoMachine laser_into_machine(const machine::Model& model, const LaserLineRuns& runs, const std::string& folder,
                                    const std::string& comment) {
  LaserIntoMachine result;
  const LaserSetup& setup = runs.setup;
  const tables::ErrorSymbol& symbol = setup.error;
  const machine::Axis& axis = model.axes[static_cast<std::size_t>(setup.joint)];
  if (axis.type == machine::AxisType::Rotary &&
      std::string("XYZABC")[static_cast<std::size_t>(symbol.component)] != axis.letter)
    throw std::runtime_error(symbol.name() +
                             ": of a rotary axis a laser or an angular reference measures its positioning (" +
                             std::string("E") + axis.letter + axis.letter +
                             ") only; its run-outs and tilts come from a "
                             "sphere or an R-test (identify sphere)");

  const bool straightness =
      axis.type == machine::AxisType::Linear && symbol.component < 3 && "XYZ"[symbol.component] != axis.letter;
  const bool referenced = runs.reference == Reference::LeastSquares || runs.reference == Reference::EndPoints;
  if (referenced && !straightness)
    throw std::runtime_error(std::string("--reference ") + reference_name(runs.reference) + " is for a straightness; " +
                             symbol.name() + " takes none or datum");

  // What the file is to read: the runs (Datum: their value at the first target replaced by what
  // the file reads there: the laser's zero is not the machine's).
  // A referenced straightness's slope goes into a squareness; where none can hold it, the runs'
  // line is replaced by the file's (its offset kept: the runs' own).
  const std::vector<double> before = readings(model, runs);
  result.runs_reference = reference_line(runs.targets, runs.readings, runs.reference);
  result.file_reference = reference_line(runs.targets, before, runs.reference);
  const std::optional<tables::ErrorSymbol> term = referenced ? squareness_term(model, runs) : std::nullopt;
  for (std::size_t k = 0; k < runs.targets.size(); ++k) {
    double aimed = runs.readings[k];
    if (runs.reference == Reference::Datum) aimed += result.file_reference.offset - result.runs_reference.offset;
    if (referenced && !term)
      aimed += (result.file_reference.slope - result.runs_reference.slope) * (runs.targets[k] - runs.targets.front());
    result.aimed.push_back(aimed);
  }
  LineUnknowns unknowns;
  unknowns.reference = runs.reference;
  if (term) {
    result.squareness = term->name();
    unknowns.squareness_joint = model.joint_of(term->axis);
    unknowns.squareness_component = term->component;
    result.squareness_before_rad =
        model.axes[static_cast<std::size_t>(unknowns.squareness_joint)].location_rad[term->component - 3];
  }
  const bool full_turn = axis.type == machine::AxisType::Rotary && runs.targets.size() > 2 &&
                         std::abs(runs.targets.back() - runs.targets.front() - 360.0) < 1e-9;
  if (full_turn) result.aimed.front() = result.aimed.back() = (result.aimed.front() + result.aimed.back()) / 2;

  tables::GridVariable grid;
  grid.axis = symbol.axis;
  grid.rotary = axis.type == machine::AxisType::Rotary;
  grid.periodic = full_turn;
  grid.nodes = runs.targets;
  result.table_file = std::string(1, static_cast<char>(std::tolower(symbol.axis))) + "_" + symbol.name() + "_laser.csv";
  shop::ExtraTable identified{
      setup.joint, result.table_file,
      tables::ErrorTable(result.table_file, {grid}, {{symbol, {result.table_file}}},
                         std::vector<double>(runs.targets.size(), 0.0), tables::Interpolation::Linear),
      runs.comments};
  std::vector<shop::ExtraTable> extras = replacing_tables(model, setup, identified, result);

  const fs::path out = fs::absolute(folder).lexically_normal();
  fs::create_directories(out);
  for (const machine::BoundTable& b : model.tables)
    if (fs::equivalent(out, fs::absolute(b.table.path()).parent_path()))
      throw std::runtime_error("--machine-out " + folder + ": a folder of the machine's tables (" + b.table.path() +
                               "); give a new one");
  if (fs::equivalent(out, fs::absolute(model.path).parent_path()))
    throw std::runtime_error("--machine-out " + folder + ": the machine file's own folder; give a new one");

  // Staged beside the folder (the same relative paths to the machine's other tables): the
  // structure written and loaded, the column solved on it, written again and read back.
  const fs::path staging = out.parent_path() / ("." + out.filename().string() + ".partial");
  fs::remove_all(staging);
  struct Cleanup {
    fs::path path;
    ~Cleanup() {
      std::error_code ignored;
      fs::remove_all(path, ignored);
    }
  } cleanup{staging};
  std::vector<shop::LocationValue> locations;
  const auto write = [&](const fs::path& where) {
    return shop::write_machine_with_tables(model, where.string(), extras, comment, locations);
  };
  machine::Model staged = machine::load_machine(write(staging));
  unknowns.table = table_index(staged, setup.joint, result.table_file);
  const LineSolution solution = solve_line(staged, unknowns, setup, runs.targets, result.aimed);
  result.table = solution.values;
  for (std::size_t i = 0; i < solution.values.size(); ++i)
    extras.back().table.set_value(static_cast<int>(i), 0, solution.values[i]);
  if (term) {
    result.squareness_rad = solution.squareness_rad;
    locations.push_back({unknowns.squareness_joint, unknowns.squareness_component, solution.squareness_rad});
  }

  // The self-check: the file as written must read the runs within their noise.
  const machine::Model check = machine::load_machine(write(staging));
  result.written_reads = readings(check, runs);
  const bool length = symbol.component < 3;
  const double floor = length ? 2e-6 : 2e-9;  // the table's digits: 1 nm, 1 nrad
  for (std::size_t k = 0; k < runs.targets.size(); ++k) {
    const double misfit = std::abs(result.written_reads[k] - result.aimed[k]);
    result.largest_misfit = std::max(result.largest_misfit, misfit);
    const double allowed = std::max(floor, 2 * runs.noise[k]);
    if (misfit > allowed) {
      const double unit = length ? 1e3 : 1e6;
      throw std::runtime_error("the written file does not read the runs: " + symbol.name() + " at " +
                               number_text(runs.targets[k]) + (grid.rotary ? " deg" : " mm") + " reads " +
                               fixed_text(result.written_reads[k] * unit, 4) + " where the runs read " +
                               fixed_text(result.aimed[k] * unit, 4) + (length ? " um" : " urad") + " (allowed " +
                               fixed_text(allowed * unit, 4) + "): nothing written");
    }
  }
  result.written = write(out);
  machine::load_machine(result.written);  // it loads where it was written
  return result;
}

}  // namespace vc::identify
