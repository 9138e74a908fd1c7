// A study's two CSV files (plain numbers, '.' decimals whatever the locale, units in the
// header, '#' comment lines first: a spreadsheet opens them):
//   report.csv  per tool length and pose set: M and Delta (um) of the four compensations;
//   tables.csv  every table's nodes: position (mm or deg) and value (um for a linear joint,
//               arcsec for a rotary joint or a squareness), modified and usual practice.
#pragma once

#include <ostream>

#include "vc/fit_tables/study.hpp"

namespace vc::fit_tables {

void write_report_csv(const Study& study, const machine::Model& model, const Controller& controller,
                      const StudyOptions& options, std::ostream& out);
void write_tables_csv(const Study& study, const machine::Model& model, const Controller& controller, std::ostream& out);

// A value of x in the unit tables.csv writes it in: um (linear output), arcsec (rotary output,
// squareness); and that unit's name.
double display_value(const machine::Model& model, const Table& table, double x);
const char* display_unit(const machine::Model& model, const Table& table);

}  // namespace vc::fit_tables
