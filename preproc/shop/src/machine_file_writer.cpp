#include "vc/shop/machine_file_writer.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>

#include "vc/machine/toml_file.hpp"
#include "vc/tables/atomic_file.hpp"
#include "vc/tables/number_text.hpp"
#include "vc/tables/symbols.hpp"
#include "vc/tables/units.hpp"

namespace vc::shop {
namespace {

namespace fs = std::filesystem;

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  return b == std::string::npos ? std::string() : s.substr(b);
}

// One array-of-tables element of a chain ([[workpiece_chain]] / [[tool_chain]]).
struct AxisSection {
  char letter;
  std::string chain;  // "workpiece_chain" or "tool_chain"
  int header_line;    // 0-based
};

// Where the first line of an axis section's sub-tables ([chain.x], [[chain.x]]) or the next
// section is, before the comments that lead into it: where lines of the axis's own go.
int end_of_axis_keys(const std::vector<std::string>& lines, int header_line) {
  int at = header_line + 1;
  while (at < static_cast<int>(lines.size()) && trimmed(lines[static_cast<std::size_t>(at)]).rfind('[', 0) != 0) ++at;
  while (at > header_line + 1) {
    const std::string t = trimmed(lines[static_cast<std::size_t>(at - 1)]);
    if (!t.empty() && t[0] != '#') break;
    --at;
  }
  return at;
}

// A location error of the axis `letter`: the value of its key replaced (in the key's unit,
// the old value kept in the comment), or a key added to the axis's location table (created
// if the axis has none), in um or arcsec.
void write_location(const LocationValue& v, char letter, const std::string& chain, const toml::table& axis,
                    int header_line, const std::vector<std::string>& lines, std::map<int, std::string>& replaced,
                    std::map<int, std::vector<std::string>, std::greater<>>& insertions, const std::string& comment) {
  const std::string symbol = tables::ErrorSymbol{v.component, letter, true}.name();
  const toml::table* location = axis["location"].as_table();
  // The uncertainty in the unit of the key that receives the value (mm or um, arcsec or urad ...).
  const auto with_uncertainty = [&](const std::string& text, const tables::Unit& unit) {
    if (v.uncertainty < 0) return text;
    return text + " +- " + number_text(std::round(v.uncertainty / unit.to_core * 1e6) / 1e6 + 0.0) + " " +
           std::string(unit.name) + " (standard uncertainty)";
  };
  int last_key_line = -1;
  if (location) {
    for (auto&& [key, node] : *location) {
      const int line = static_cast<int>(key.source().begin.line) - 1;
      last_key_line = std::max(last_key_line, line);
      const std::string k(key.str());
      const std::size_t underscore = k.rfind('_');
      if (underscore == std::string::npos || k.substr(0, underscore) != symbol) continue;
      const auto unit = tables::find_unit(k.substr(underscore + 1));
      if (!unit) throw std::runtime_error("unknown unit in " + k);
      std::string& text =
          replaced.count(line) ? replaced[line] : (replaced[line] = lines[static_cast<std::size_t>(line)]);
      const auto begin = static_cast<std::size_t>(node.source().begin.column) - 1;
      const auto end = static_cast<std::size_t>(node.source().end.column) - 1;
      if (node.source().end.line != node.source().begin.line || end > text.size() || begin >= end)
        throw std::runtime_error("line " + std::to_string(line + 1) + ": cannot rewrite the value of " + k);
      const std::string old = text.substr(begin, end - begin);
      text =
          text.substr(0, begin) + number_text(std::round(v.value / unit->to_core * 1e6) / 1e6 + 0.0) + text.substr(end);
      text +=
          (text.find('#') == std::string::npos ? "   # " : "; ") + with_uncertainty(comment, *unit) + ", was " + old;
      return;
    }
  }
  const bool length = v.component < 3;
  const std::string line = symbol + (length ? "_um = " : "_arcsec = ") +
                           number_text(std::round(v.value * (length ? 1e3 : 648000.0 / M_PI) * 1e6) / 1e6 + 0.0) +
                           "   # " + with_uncertainty(comment, *tables::find_unit(length ? "um" : "arcsec"));
  if (location && last_key_line >= 0) {
    insertions[last_key_line + 1].push_back(line);
  } else if (location) {
    insertions[static_cast<int>(location->source().begin.line)].push_back(line);  // after its header
  } else {  // a new location table; several values share it
    const std::string header = "[" + chain + ".location]";
    std::vector<std::string>& block = insertions[end_of_axis_keys(lines, header_line)];
    if (std::find(block.begin(), block.end(), header) == block.end()) block.push_back(header);
    block.push_back(line);
  }
}

}  // namespace

void write_table_csv(const tables::ErrorTable& table, const std::string& path,
                     const std::vector<std::string>& comments) {
  tables::write_atomically(path, [&](std::ostream& out) { write_table_csv(table, out, comments); });
}

void write_table_csv(const tables::ErrorTable& table, std::ostream& out, const std::vector<std::string>& comments) {
  for (const std::string& c : comments) out << "# " << c << '\n';
  const auto& grid = table.grid();
  for (std::size_t v = 0; v < grid.size(); ++v) out << (v ? "," : "") << grid[v].name() << '[' << grid[v].unit() << ']';
  for (const auto& c : table.columns())
    out << ',' << c.symbol.name() << (c.symbol.quantity() == tables::Quantity::Length ? "[um]" : "[urad]");
  out << '\n';
  // Rows in node order, first variable slowest (as the loader reads them).
  std::vector<std::size_t> index(grid.size(), 0);
  for (int node = 0; node < table.node_count(); ++node) {
    int rest = node;
    for (std::size_t v = grid.size(); v-- > 0;) {
      index[v] = static_cast<std::size_t>(rest) % grid[v].nodes.size();
      rest /= static_cast<int>(grid[v].nodes.size());
    }
    for (std::size_t v = 0; v < grid.size(); ++v) out << (v ? "," : "") << number_text(grid[v].nodes[index[v]] + 0.0);
    for (std::size_t c = 0; c < table.columns().size(); ++c) {
      // um or urad, to a thousandth of them
      const bool length = table.columns()[c].symbol.quantity() == tables::Quantity::Length;
      out << ','
          << number_text(std::round(table.value(node, static_cast<int>(c)) * (length ? 1e6 : 1e9)) / 1e3 +
                         0.0);  // no "-0"
    }
    out << '\n';
  }
}

tables::ErrorTable zero_table(const machine::Model& model, int joint, int nodes,
                              const std::vector<tables::ErrorSymbol>& columns, const std::string& path) {
  const machine::Axis& axis = model.axes[static_cast<std::size_t>(joint)];
  tables::GridVariable g;
  g.axis = axis.letter;
  g.rotary = axis.type == machine::AxisType::Rotary;
  for (int i = 0; i < nodes; ++i)
    g.nodes.push_back(axis.travel_min + (axis.travel_max - axis.travel_min) * i / (nodes - 1));
  // A full turn is periodic (tables/README.md): its first and last rows must be equal.
  g.periodic = g.rotary && std::abs(std::abs(g.nodes.back() - g.nodes.front()) - 360.0) <= 1e-9;
  std::vector<tables::Column> cols;
  for (const auto& s : columns) cols.push_back({s, {path}});
  return tables::ErrorTable(path, {g}, cols, std::vector<double>(static_cast<std::size_t>(nodes) * columns.size(), 0.0),
                            tables::Interpolation::Linear);
}

std::string write_machine_with_tables(const machine::Model& model, const std::string& folder,
                                      const std::vector<ExtraTable>& extras, const std::string& comment,
                                      const std::vector<LocationValue>& locations) {
  const fs::path source(model.path);
  const fs::path base = source.parent_path();
  std::vector<std::string> lines;
  {
    std::ifstream in(source);
    if (!in) throw std::runtime_error("cannot read " + model.path);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
  }
  fs::create_directories(folder);
  const fs::path out_dir = fs::absolute(folder);
  const machine::TomlFile machine_file(model.path);  // the model loaded from it: it parses
  const toml::table& root = machine_file.root();

  std::map<int, std::string> replaced_lines;                           // 0-based line -> new text
  std::map<int, std::vector<std::string>, std::greater<>> insertions;  // before 0-based line, last first
  std::vector<AxisSection> sections;
  std::vector<std::pair<char, std::string>> existing;  // (axis, file name) already listed
  for (const char* chain : {"workpiece_chain", "tool_chain"}) {
    const toml::array* axes = root[chain].as_array();
    if (!axes) continue;
    for (const toml::node& element : *axes) {
      const toml::table& axis = *element.as_table();
      const char letter = axis["axis"].value_or(std::string("?"))[0];
      sections.push_back({letter, chain, static_cast<int>(element.source().begin.line) - 1});
      for (const LocationValue& v : locations)
        if (model.axes[static_cast<std::size_t>(v.joint)].letter == letter)
          write_location(v, letter, chain, axis, sections.back().header_line, lines, replaced_lines, insertions,
                         comment);
      const toml::array* list = axis["tables"].as_array();
      if (!list) continue;
      for (const toml::node& t : *list) {
        const toml::node* file = t.as_table()->get("file");
        const std::string value = file->value_or(std::string());
        const std::string name = fs::path(value).filename().string();
        existing.emplace_back(letter, name);
        // The path as seen from the new folder: the extra table itself, or the original.
        const bool is_extra = std::any_of(extras.begin(), extras.end(), [&](const ExtraTable& e) {
          return e.file_name == name && model.axes[static_cast<std::size_t>(e.joint)].letter == letter;
        });
        const std::string target = is_extra ? name : fs::relative(fs::absolute(base / value), out_dir).generic_string();
        const int line = static_cast<int>(file->source().begin.line) - 1;
        std::string& text = replaced_lines.count(line) ? replaced_lines[line] : (replaced_lines[line] = lines[line]);
        const auto open = static_cast<std::size_t>(file->source().begin.column) - 1;
        const char quote = text[open];
        const auto close = text.find(quote, open + 1);
        if ((quote != '"' && quote != '\'') || close == std::string::npos)
          throw std::runtime_error(model.path + ":" + std::to_string(line + 1) + ": cannot rewrite this table path");
        text = text.substr(0, open) + '"' + target + '"' + text.substr(close + 1);
      }
    }
  }
  for (const auto& [line, text] : replaced_lines) lines[static_cast<std::size_t>(line)] = text;

  // New tables go at the end of their axis's section: before the next header that is not
  // one of its sub-tables, and before the comments that lead into that header.
  for (const ExtraTable& e : extras) {
    const char letter = model.axes[static_cast<std::size_t>(e.joint)].letter;
    std::vector<std::string> comments = {comment, "error = actual - nominal; summed with the axis's other tables",
                                         "units: positions mm or deg, translations um, rotations urad"};
    comments.insert(comments.end(), e.comments.begin(), e.comments.end());
    if (e.text.empty()) {
      write_table_csv(e.table, (out_dir / e.file_name).string(), comments);
    } else {
      tables::write_atomically((out_dir / e.file_name).string(), [&](std::ostream& copy) { copy << e.text; });
    }
    if (std::find(existing.begin(), existing.end(), std::pair(letter, e.file_name)) != existing.end()) continue;
    const auto section =
        std::find_if(sections.begin(), sections.end(), [&](const AxisSection& s) { return s.letter == letter; });
    if (section == sections.end())
      throw std::runtime_error("axis " + std::string(1, letter) + " has no section in " + model.path);
    int at = section->header_line + 1;
    while (at < static_cast<int>(lines.size())) {
      const std::string t = trimmed(lines[static_cast<std::size_t>(at)]);
      if (!t.empty() && t[0] == '[' && t.rfind("[" + section->chain + ".", 0) != 0 &&
          t.rfind("[[" + section->chain + ".", 0) != 0)
        break;
      ++at;
    }
    while (at > section->header_line + 1) {
      const std::string t = trimmed(lines[static_cast<std::size_t>(at - 1)]);
      if (!t.empty() && t[0] != '#') break;
      --at;
    }
    insertions[at].insert(insertions[at].end(),
                          {"[[" + section->chain + ".tables]]", "file = \"" + e.file_name + "\"   # " + comment});
  }
  for (const auto& [at, text] : insertions) lines.insert(lines.begin() + at, text.begin(), text.end());

  // The machine file last: killed before it, the folder keeps the old machine file, complete,
  // beside the new tables (each also complete).
  const fs::path machine_out = out_dir / source.filename();
  tables::write_atomically(machine_out.string(), [&](std::ostream& out) {
    for (const std::string& l : lines) out << l << '\n';
  });
  return machine_out.string();
}

}  // namespace vc::shop
