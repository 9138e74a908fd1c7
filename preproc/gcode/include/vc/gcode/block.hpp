// One line of a G-code program as read: what is written on it and where, before any meaning
// is given to it. Offsets are 0-based byte offsets into the raw line, so a tool that rewrites
// a block can cut a word out of the original text and messages can name the column.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "vc/gcode/ast.hpp"

namespace vc::gcode {

struct Word {
  char letter;            // upper case: 'G', 'X', ...
  ast::Expression value;  // a number or an expression: evaluate(value, parameters)
  int begin, end;         // [begin, end) of the word in the raw line (letter to value's end)
};

// #n = value, #<name> = value. LinuxCNC sets them after the whole line is read: every
// reference on the line sees the old values (apply_assignments).
struct Assignment {
  ast::Expression target;  // an ast::NumberedParameter or ast::NamedParameter
  ast::Expression value;
  int begin, end;
};

struct Comment {
  std::string text;  // without the delimiters, as written (case kept)
  int begin, end;    // including '(' ')' or ';'
};

// An O word: control flow (LinuxCNC's subroutines, loops, conditions), or a Fanuc-style
// program number "O1000" (kind None) that M98 calls.
struct OWord {
  enum class Kind {
    None,
    Sub,
    EndSub,
    Call,
    Do,
    While,
    EndWhile,
    If,
    ElseIf,
    Else,
    EndIf,
    Break,
    Continue,
    Return,
    Repeat,
    EndRepeat
  };
  Kind kind = Kind::None;
  std::string name;            // "100" for o100 and o0100, "name" for o<Name> (lower case)
  bool computed_name = false;  // o[expression] or o#n: the number is name_expression's value
  ast::Expression name_expression;
  std::vector<ast::Expression> args;  // call: [arguments]; while, if, elseif, repeat: [condition or
                                      // count]; endsub, return: [value], if any
  int begin = -1, end = -1;           // the O word in the raw line; end: after its last argument
};

struct Block {
  bool percent = false;       // a '%' program delimiter line
  bool block_delete = false;  // starts with '/'
  bool has_line_number = false;
  double line_number = 0;   // N word (LinuxCNC allows N only at the start, after '/')
  int o_word = -1;          // offset of an O word (subroutines, loops): -1 if none
  OWord o;                  // the O word, if o_word >= 0
  std::vector<Word> words;  // in the order written
  std::vector<Assignment> assignments;
  std::vector<Comment> comments;

  // Empties the block, keeping the vectors' capacity (one Block serves a whole program).
  void clear() {
    percent = block_delete = has_line_number = false;
    line_number = 0;
    o_word = -1;
    if (!o.name.empty() || o.computed_name) o = OWord{};
    words.clear();
    assignments.clear();
    comments.clear();
  }
};

}  // namespace vc::gcode
