// The volume map drawn (volume_map.hpp): one picture per tool length and rotary setting, a heat
// map of |e| (um) over the map's plane (X-Y) per level of the third joint (Z, columns) and per
// compensation (rows: none, the usual practice's tables, the modified method's), every panel on
// the same colour scale (0 to the sheet's largest uncompensated |e|), so that the rows compare
// at a glance; each panel's title gives its largest |e|. The full correction is not drawn (0 on
// the model): full_correction_statement() says so under the title.
#pragma once

#include <cstddef>
#include <string>

#include "vc/plot/gnuplot.hpp"
#include "vc/plot/volume_map.hpp"

namespace vc::plot {

// The figure for draw(): data (one block per compensation and level: X, Y in mm and |e| in um,
// gnuplot's `index` order: compensation-major) and script.
Figure volume_map_plot(const VolumeMap& map, std::size_t sheet, const machine::Model& model, const std::string& image);

// A file name for a sheet: "volume_L100_rotary0", "volume_L100_worst" (no extension).
std::string volume_map_name(const MapSheet& sheet);

}  // namespace vc::plot
