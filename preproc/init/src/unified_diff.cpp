#include "vc/init/unified_diff.hpp"

#include <algorithm>
#include <stdexcept>

namespace vc::init {

void FileEdits::replace(int line, std::string text) {
  if (removed(line)) throw std::logic_error("replacing a removed line");
  changed_[line] = std::move(text);
}

void FileEdits::remove(int line) { changed_[line] = std::nullopt; }

void FileEdits::insert_after(int line, const std::vector<std::string>& texts) {
  std::vector<std::string>& at = inserted_[line];
  at.insert(at.end(), texts.begin(), texts.end());
}

bool FileEdits::removed(int line) const {
  const auto it = changed_.find(line);
  return it != changed_.end() && !it->second;
}

std::vector<FileEdits::Op> FileEdits::operations() const {
  const std::vector<TextLine>& old = file_->lines;
  const int n = static_cast<int>(old.size());
  auto end_after = [&](int line) {  // the line end of inserted lines
    if (line >= 1 && !old[static_cast<std::size_t>(line - 1)].end.empty())
      return old[static_cast<std::size_t>(line - 1)].end;
    return old.empty() || old.front().end.empty() ? std::string("\n") : old.front().end;
  };
  std::vector<Op> ops;
  auto insert = [&](int after) {
    if (const auto it = inserted_.find(after); it != inserted_.end())
      for (const std::string& text : it->second) ops.push_back({'+', {text, end_after(after)}});
  };
  insert(0);
  for (int i = 1; i <= n; ++i) {
    const TextLine& line = old[static_cast<std::size_t>(i - 1)];
    TextLine now = line;
    bool keep = true;
    if (const auto it = changed_.find(i); it != changed_.end()) {
      keep = it->second.has_value();
      if (keep) now.text = *it->second;
    }
    // A last line without a newline gets one when lines follow it.
    if (i == n && now.end.empty() && inserted_.count(n)) now.end = end_after(0);
    if (!keep)
      ops.push_back({'-', line});
    else if (now.text == line.text && now.end == line.end)
      ops.push_back({' ', line});
    else {
      ops.push_back({'-', line});
      ops.push_back({'+', now});
    }
    insert(i);
  }
  // Within each run of changes, the removed lines first (as diff writes them).
  for (std::size_t i = 0; i < ops.size();) {
    std::size_t j = i;
    while (j < ops.size() && ops[j].kind != ' ') ++j;
    std::stable_partition(ops.begin() + static_cast<long>(i), ops.begin() + static_cast<long>(j),
                          [](const Op& op) { return op.kind == '-'; });
    i = j == i ? i + 1 : j;
  }
  return ops;
}

FileEdits::Counts FileEdits::counts() const {
  Counts n;
  for (const Op& op : operations()) {
    n.removed += op.kind == '-';
    n.added += op.kind == '+';
  }
  return n;
}

std::vector<TextLine> FileEdits::result() const {
  std::vector<TextLine> lines;
  for (const Op& op : operations())
    if (op.kind != '-') lines.push_back(op.line);
  return lines;
}

std::string FileEdits::unified_diff(const std::string& name, int context) const {
  const std::vector<Op> ops = operations();
  const std::size_t count = ops.size();
  // Old and new line numbers before each operation.
  std::vector<int> old_before(count + 1, 0), new_before(count + 1, 0);
  for (std::size_t i = 0; i < count; ++i) {
    old_before[i + 1] = old_before[i] + (ops[i].kind != '+');
    new_before[i + 1] = new_before[i] + (ops[i].kind != '-');
  }
  auto range = [](int before, int lines) {
    const int start = lines == 0 ? before : before + 1;
    return std::to_string(start) + (lines == 1 ? "" : "," + std::to_string(lines));
  };
  std::string diff;
  const auto ctx = static_cast<std::size_t>(context);
  for (std::size_t i = 0; i < count;) {
    if (ops[i].kind == ' ') {
      ++i;
      continue;
    }
    const std::size_t begin = i >= ctx ? i - ctx : 0;
    std::size_t end = i;  // one past the hunk's last change
    for (;;) {
      while (end < count && ops[end].kind != ' ') ++end;
      std::size_t next = end;
      while (next < count && ops[next].kind == ' ') ++next;
      if (next < count && next - end <= 2 * ctx) {  // the next change's context touches this one's
        end = next;
        continue;
      }
      end = std::min(count, end + ctx);
      break;
    }
    if (diff.empty()) diff = "--- a/" + name + "\n+++ b/" + name + "\n";
    diff += "@@ -" + range(old_before[begin], old_before[end] - old_before[begin]) + " +" +
            range(new_before[begin], new_before[end] - new_before[begin]) + " @@\n";
    for (std::size_t k = begin; k < end; ++k) {
      diff += ops[k].kind + ops[k].line.text + ops[k].line.end;
      if (ops[k].line.end.empty()) diff += "\n\\ No newline at end of file\n";
    }
    i = end;
  }
  return diff;
}

std::string creation_diff(const std::string& name, const std::vector<TextLine>& lines) {
  std::string diff = "--- /dev/null\n+++ b/" + name + "\n@@ -0,0 +1" +
                     (lines.size() == 1 ? "" : "," + std::to_string(lines.size())) + " @@\n";
  for (const TextLine& line : lines) {
    diff += "+" + line.text + line.end;
    if (line.end.empty()) diff += "\n\\ No newline at end of file\n";
  }
  return diff;
}

}  // namespace vc::init
