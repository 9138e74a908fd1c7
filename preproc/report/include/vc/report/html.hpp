// Pieces of the report's HTML: text escaped, tables, a picture embedded as a data: URI (the
// page needs no other file and makes no request).
#pragma once

#include <string>
#include <vector>

namespace vc::report {

// & < > " ' as entities.
std::string escaped(const std::string& text);

// A table: its header cells (none: no header row) and rows, every cell escaped; `numeric`
// right-aligns the columns after the first.
std::string html_table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows,
                       bool numeric = true);

// How much of a printed A4 page a figure may take: half (two a page: the axis plots, the
// balance, the ISO plots) or the whole page's height (the volume map's panels).
enum class FigureSize { Half, Full };

// <figure> with the PNG embedded (base64) and its caption (escaped); `alt` says what it shows.
std::string html_png_figure(const std::string& png_bytes, const std::string& alt, const std::string& caption,
                            FigureSize size = FigureSize::Half);

// A file's path as the page names it: absolute, normalised.
std::string shown_path(const std::string& path);

// Fixed decimals, whatever the locale.
std::string fixed(double v, int decimals);

}  // namespace vc::report
