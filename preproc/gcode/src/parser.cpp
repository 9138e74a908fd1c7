// parse_block: LinuxCNC's line reading. First the line is normalized as LinuxCNC does
// (comments taken out, spaces and tabs dropped, letters lower-cased), keeping where each
// character came from; then words and assignments are read one after the other, their
// values and expressions by the X3 grammar (parser_def.hpp), the only file that includes it.
#include "vc/gcode/parser.hpp"

#include <array>
#include <cctype>
#include <string>
#include <vector>

#include "parser_def.hpp"

namespace vc::gcode {
namespace {

namespace x3 = boost::spirit::x3;

// The line without comments and blanks, lower case, and the raw offset of each character.
struct Normalized {
  std::string text;
  std::vector<int> raw;  // raw offset of text[i]; raw[text.size()] = end of the raw line
};

std::string describe(char c) {
  if (std::isprint(static_cast<unsigned char>(c))) return std::string("'") + c + "'";
  return "byte " + std::to_string(static_cast<unsigned char>(c));
}

// What normalize does with each byte: 0 skip it (space, tab), 1 look closer (comments, a
// stray ')', bytes that are not printable), else keep this (the byte, lower-cased).
constexpr std::array<unsigned char, 256> kNormalizeMap = [] {
  std::array<unsigned char, 256> map{};
  for (int c = 0; c < 256; ++c) {
    if (c == ' ' || c == '\t')
      map[c] = 0;
    else if (c < ' ' || c > '~' || c == ';' || c == '(' || c == ')')  // isprint in the "C" locale
      map[c] = 1;
    else
      map[c] = static_cast<unsigned char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  }
  return map;
}();

void normalize(std::string_view line, Normalized& n, Block& block) {
  // Written through pointers into buffers sized for the whole line, one table lookup per
  // character (this runs per character).
  n.text.resize(line.size());
  n.raw.resize(line.size() + 1);
  char* text = n.text.data();
  int* raw = n.raw.data();
  std::size_t kept = 0;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    const unsigned char mapped = kNormalizeMap[static_cast<unsigned char>(c)];
    if (mapped > 1) {
      text[kept] = static_cast<char>(mapped);
      raw[kept++] = static_cast<int>(i);
      continue;
    }
    if (mapped == 0) continue;
    if (c == ';') {
      block.comments.push_back({std::string(line.substr(i + 1)), static_cast<int>(i), static_cast<int>(line.size())});
      break;
    }
    if (c == '(') {
      const std::size_t close = line.find_first_of("()", i + 1);
      if (close == std::string_view::npos) throw SyntaxError(static_cast<int>(i), "unclosed comment: '(' without ')'");
      if (line[close] == '(') throw SyntaxError(static_cast<int>(close), "nested comment: '(' inside a comment");
      block.comments.push_back(
          {std::string(line.substr(i + 1, close - i - 1)), static_cast<int>(i), static_cast<int>(close + 1)});
      i = close;
      continue;
    }
    if (c == ')') throw SyntaxError(static_cast<int>(i), "')' without '('");
    throw SyntaxError(static_cast<int>(i), "unexpected " + describe(c) + " (not a printable character)");
  }
  raw[kept] = static_cast<int>(line.size());
  n.text.resize(kept);
  n.raw.resize(kept + 1);
}

// Parses `rule` at text[pos...]; returns the end position. X3's expectation failures
// become SyntaxErrors at the raw offset where the expected thing is missing; `expected()`
// says what was expected at pos (called only then).
template <typename Rule, typename Attribute, typename Expected>
std::size_t parse_at(const Normalized& n, std::size_t pos, const Rule& rule, Attribute& attribute,
                     const Expected& expected) {
  auto first = n.text.begin() + static_cast<std::ptrdiff_t>(pos);
  const auto last = n.text.end();
  try {
    if (!x3::parse(first, last, rule, attribute)) throw SyntaxError(n.raw[pos], "expected " + std::string(expected()));
  } catch (const x3::expectation_failure<std::string::const_iterator>& e) {
    const auto at = static_cast<std::size_t>(e.where() - n.text.begin());
    const std::string found = at < n.text.size() ? ", found " + describe(n.text[at]) : ", found the end of the line";
    throw SyntaxError(n.raw[at], "expected " + e.which() + found);
  }
  return static_cast<std::size_t>(first - n.text.begin());
}

bool is_word_letter(char c) {
  // RS274/NGC word letters LinuxCNC knows (O is not a word; N only at the start; E is G76's).
  // '@' and '^': polar coordinates (distance, angle in degrees) in the XY plane.
  return std::string_view("abcdefghijklmpqrstuvwxyz@^").find(c) != std::string_view::npos;
}

// "o<name> keyword [arg]..." or "o123 keyword ...": the rest of the (normalized) line.
void parse_o_word(const Normalized& n, std::size_t pos, Block& block) {
  using Kind = OWord::Kind;
  OWord& o = block.o;
  o.begin = block.o_word = n.raw[pos];
  ++pos;
  const std::string& text = n.text;
  if (pos < text.size() && text[pos] == '<') {
    const std::size_t close = text.find('>', pos);
    if (close == std::string::npos) throw SyntaxError(n.raw[pos], "expected '>' to end the O-word name");
    o.name = text.substr(pos + 1, close - pos - 1);
    if (o.name.empty()) throw SyntaxError(n.raw[pos], "an empty O-word name");
    pos = close + 1;
  } else if (pos < text.size() && (text[pos] == '[' || text[pos] == '#')) {
    // o[expression] and o#n (LinuxCNC's read_o): the O number is computed when the line runs.
    o.computed_name = true;
    pos = parse_at(n, pos, parser::value, o.name_expression, [] { return "an O number"; });
  } else {
    std::size_t digits = pos;
    while (digits < text.size() && std::isdigit(static_cast<unsigned char>(text[digits]))) ++digits;
    if (digits == pos) throw SyntaxError(n.raw[pos], "expected a number, <name>, [expression] or #parameter after 'O'");
    const std::size_t first = text.find_first_not_of('0', pos);
    o.name = first < digits ? text.substr(first, digits - first) : "0";  // o0100 is o100
    pos = digits;
  }
  std::size_t letters = pos;
  while (letters < text.size() && std::isalpha(static_cast<unsigned char>(text[letters]))) ++letters;
  static constexpr std::pair<std::string_view, Kind> kKeywords[] = {
      {"sub", Kind::Sub},       {"endsub", Kind::EndSub}, {"call", Kind::Call},
      {"do", Kind::Do},         {"while", Kind::While},   {"endwhile", Kind::EndWhile},
      {"if", Kind::If},         {"elseif", Kind::ElseIf}, {"else", Kind::Else},
      {"endif", Kind::EndIf},   {"break", Kind::Break},   {"continue", Kind::Continue},
      {"return", Kind::Return}, {"repeat", Kind::Repeat}, {"endrepeat", Kind::EndRepeat}};
  const std::string_view keyword = std::string_view(text).substr(pos, letters - pos);
  o.kind = Kind::None;
  if (!keyword.empty()) {
    bool known = false;
    for (const auto& [name, kind] : kKeywords)
      if (keyword == name) {
        o.kind = kind;
        known = true;
      }
    if (!known) throw SyntaxError(n.raw[pos], "unknown O-word keyword '" + std::string(keyword) + "'");
  }
  pos = letters;
  while (pos < text.size()) {
    if (text[pos] != '[') throw SyntaxError(n.raw[pos], "expected '[' (an O-word argument is an [expression])");
    ast::Expression& e = o.args.emplace_back();
    pos = parse_at(n, pos, parser::value, e, [] { return "an [expression]"; });
  }
  o.end = n.raw[pos > 0 ? pos - 1 : 0] + 1;
  const bool one = o.kind == Kind::While || o.kind == Kind::If || o.kind == Kind::ElseIf || o.kind == Kind::Repeat;
  const bool optional = o.kind == Kind::EndSub || o.kind == Kind::Return;
  const bool any = o.kind == Kind::Call;
  if ((one && o.args.size() != 1) || (optional && o.args.size() > 1) || (!one && !optional && !any && !o.args.empty()))
    throw SyntaxError(o.begin, one ? "this O word needs one [expression]" : "too many [arguments] for this O word");
  if (o.args.size() > 30) throw SyntaxError(o.begin, "a call passes at most 30 arguments (#1..#30)");
}

}  // namespace

void parse_block(std::string_view line, Block& block) {
  block.clear();
  thread_local Normalized normalized;
  Normalized& n = normalized;  // one thread-local lookup per line, not one per use
  normalize(line, n, block);
  std::size_t pos = 0;
  if (n.text.size() == 1 && n.text[0] == '%') {
    block.percent = true;
    return;
  }
  if (pos < n.text.size() && n.text[pos] == '/') {
    block.block_delete = true;
    ++pos;
  }
  if (pos < n.text.size() && n.text[pos] == 'n') {
    pos = parse_at(n, pos + 1, parser::number, block.line_number, [] { return "a line number after 'N'"; });
    if (block.line_number < 0) throw SyntaxError(n.raw[pos - 1], "a line number cannot be negative");
    block.has_line_number = true;
  }
  while (pos < n.text.size()) {
    const char c = n.text[pos];
    if (c == 'o') {
      if (!block.words.empty() || !block.assignments.empty())
        throw SyntaxError(n.raw[pos], "an O word must start the line (after an N number)");
      parse_o_word(n, pos, block);
      return;
    }
    if (c == '#') {
      Assignment a;
      a.begin = n.raw[pos];
      pos = parse_at(n, pos, parser::parameter, a.target, [] { return "a parameter"; });
      if (pos >= n.text.size() || n.text[pos] != '=')
        throw SyntaxError(n.raw[pos], "expected '=' after the parameter (a parameter alone is not a word)");
      pos = parse_at(n, pos + 1, parser::value, a.value, [] { return "a value after '='"; });
      a.end = n.raw[pos - 1] + 1;
      block.assignments.push_back(std::move(a));
      continue;
    }
    if (c == 'n') throw SyntaxError(n.raw[pos], "a line number (N) must start the line");
    if (!is_word_letter(c)) {
      if (std::isalpha(static_cast<unsigned char>(c)))
        throw SyntaxError(n.raw[pos], std::string("unknown word letter '") +
                                          static_cast<char>(std::toupper(static_cast<unsigned char>(c))) + "'");
      throw SyntaxError(n.raw[pos], "expected a word (letter and value), found " + describe(c));
    }
    Word& w = block.words.emplace_back();
    w.letter = c >= 'a' && c <= 'z' ? static_cast<char>(c - 'a' + 'A') : c;
    w.begin = n.raw[pos];
    // Most words carry a plain number: read it directly (what the grammar's value rule,
    // whose first alternative is the number, would read).
    double number = 0.0;
    const char* const value_text = n.text.data() + pos + 1;
    const char* const number_end = parser::scan_number(value_text, n.text.data() + n.text.size(), number);
    if (number_end != value_text) {
      w.value = number;
      pos = static_cast<std::size_t>(number_end - n.text.data());
    } else {
      pos = parse_at(n, pos + 1, parser::value, w.value,
                     [&w] { return std::string("a number or [expression] after '") + w.letter + "'"; });
    }
    w.end = n.raw[pos - 1] + 1;
  }
}

}  // namespace vc::gcode
