// The subcommands of `volcomp`. Each returns the process exit code and may throw
// vc::LoadError (bad input file) or std::exception; main() prints those.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace vc::cli {

struct CheckArgs {
  std::string machine;
  int samples = 10000;  // random poses over the travel, besides the grid of corners and mids
  std::string ini;      // a LinuxCNC configuration loading this machine: where it homes, or ""
};

struct BalanceArgs {
  std::string machine;
  int levels = 5;                        // positions per joint over the travel
  std::optional<double> tool_length_mm;  // default: the machine file's tool_length_mm
  std::string output;                    // CSV (optional)
  std::string plot;                      // bar chart, .png or .svg (optional, gnuplot; its data: .csv beside it)
};

struct FitTablesArgs {
  std::string machine;
  std::string controller;                      // a shipped controller's name or a controller file
  std::string output;                          // folder: report.csv, tables.csv, the controller's files
  std::string criterion = "minimax";           // minimax or ls
  std::vector<std::string> tool_lengths;       // mm, fitted (default: the machine file's)
  std::vector<std::string> check_tool_lengths; // mm, judged only (default: midpoints, largest + 50)
  std::vector<std::string> rotary;             // "B=-90,-60,0": rotary grid positions, deg
  std::optional<int> nodes;                    // per table (default: the controller's)
  std::optional<int> levels;                   // grid positions per joint (default: the nodes)
  int fresh = 2000;                            // random poses per tool length in each fresh set
  double ridge = 1e-2, smoothness = 1e-2;      // the fit's regularisation (fit.hpp)
  std::vector<std::string> programs;           // part programs whose poses are fitted too
  bool programs_only = false;                  // ... and nothing else (the volume judged only)
  std::string tool_table, var_file;            // LinuxCNC's files the programs are read with
  std::string machine_units = "mm";
  std::vector<std::string> reversal;           // "X=runs.csv": laser runs whose reversal the COMP_FILE takes
};

struct IdentifyLaserArgs {
  std::string runs;                // laser runs CSV
  std::string error;               // the component error they measure: EXX, EYX, EAX, ECC, ...
  std::string output;              // error table CSV (optional)
  std::string direction = "both";  // the table's value: both (mean bidirectional), up or down
  bool keep_all = false;           // keep the suspicious runs in the evaluation
  std::string machine;             // machine file whose axis takes the table (optional)
  std::string machine_out;         // folder: the table and a copy of the machine file using it
  std::string at;                  // where the axes stood, "x=0,y=-160,..." (default: the runs' "# at:")
  std::optional<double> tool_length_mm;  // the tool-side optic L below the gauge point (default: the runs')
  std::vector<double> tool_point_mm;     // ... or anywhere in the spindle frame, x,y,z from the gauge point
  std::string reference;           // datum, least-squares, end-points, none (default by the error)
  std::string squareness;          // a straightness's slope goes into this location error (e.g. EC0X)
  std::string plot;                // the ISO 230-2 graph, .png or .svg (optional, gnuplot; its data: .csv beside it)
};

struct IdentifyCircleArgs {
  std::string run;                 // circular test CSV
  std::string plane;               // XY, YZ, ZX (default: the file's "# plane:")
  std::optional<double> radius_mm; // default: the file's "# radius_mm:"
  std::string machine;             // to express the squareness in its terms (optional)
  std::string machine_out;         // folder for the machine file with the squareness set
  std::string symbol;              // which term takes it (default: the one the file uses)
  std::string plot;                // the polar plot, .png or .svg (optional, gnuplot; its data: .csv beside it)
};

struct PlotArgs {
  std::string machine;
  std::string folder;              // per axis <letter>_axis.png (or .svg) and .csv; location_errors.csv
  std::string format = "png";      // png or svg
  bool volume = false;             // also the volume map: volume_L<mm>_rotary0 / _worst images and CSVs
  std::vector<double> tool_lengths_mm;  // of the volume map (default: the machine file's)
  std::string plane;                    // of the volume map: "xz", "yz" ... (default: the first two linear axes)
  std::string controller = "linuxcnc";  // whose tables the volume map judges; "none" for none
};

struct ReportArgs {
  std::string machine;
  std::string measurements;        // folder of laser runs and circular tests (optional)
  std::string output;              // the HTML page
  std::vector<double> tool_lengths_mm;  // of the volume map (default: 0 and the machine file's)
};

struct IdentifySphereArgs {
  std::string machine;
  std::string centres;                   // CSV: the joints at the sphere's centre, one pose per row
  std::vector<std::string> deviations;   // location errors to identify (default: all of the rotary axes)
  std::optional<double> tool_length_mm;  // default: the machine file's
  std::string machine_out;               // folder for the machine file with the identified values
};

struct ProbePlanArgs {
  std::string machine;
  std::vector<double> centre;            // X,Y,Z of the sphere's centre at rotary 0 (joints, mm)
  double sphere_diameter_mm = 25.0;
  double ball_diameter_mm = 2.0;
  std::optional<double> probe_length_mm;  // default: the machine file's tool length
  std::vector<std::string> grid;         // "B=0,-30,-60" "C=0,90,180,270"
  std::string log_file = "volcomp_sphere_probe.txt";
  double clearance_mm = 3.0;             // the search starts this far off the surface
  double probe_feed_mm_min = 100.0;      // the search
  double back_off_mm = 0.3;
  double touch_feed_mm_min = 10.0;       // the measuring touch
  std::string output;                    // the program (default: stdout)
};

struct InitArgs {
  std::string ini;     // the LinuxCNC configuration's INI file
  std::string output;  // the machine file to write
  std::string patch;   // the patch's file; "" or "-": stdout
};

struct PoseArgs {
  std::string machine;
  std::string poses;
  std::optional<double> tool_length_mm;  // default: the machine file's tool_length_mm
  std::vector<std::string> only;         // deviations to keep (error): all if empty
  bool ideal_tip = false;                // error: also the ideal tool tip (tx,ty,tz)
};

struct TraceArgs {
  std::string machine;
  std::string trace;               // CSV recorded by kins/configs/common/headless_driver.py
  std::string world = "axes";      // the module's world convention
  std::string output;              // per-sample errors CSV (optional)
  double servo_period_s = 0.001;   // for the time column
  std::string comp_files;          // a folder of fit-tables' COMP_FILEs to replay on the trace (optional)
  std::string ini;                 // the configuration's INI: the joints' limits for the replay
  std::string replay_output;       // the replay's per-sample errors CSV (t_s,e_um; optional)
};

struct PredistortArgs {
  std::string machine;
  std::string input;
  std::string output;              // "-": stdout (AXIS filter)
  std::string var_file;            // LinuxCNC parameter file: work offsets, G28/G30 homes
  std::string tool_table;          // LinuxCNC tool table: tool lengths
  std::string machine_units = "mm";  // of the tool table and the .var file: mm or inch
  std::string process;             // cutting conditions per tool: cutting-force deflection
  std::string world = "axes";      // world convention of the uncompensated kinematics
  std::vector<std::string> subroutine_path;  // folders of NAME.ngc subroutine files
  std::string start;               // where the machine starts: X,Y,Z[,A,B,C] or an INI (homes)
  std::string line_map;            // CSV: output line -> input file and line
  double tolerance_mm = 0.0005;
  double tolerance_rad = 2e-5;     // tool direction between written points (rotary axes)
  std::vector<std::string> temperatures;  // NAME=VALUE (degC) of the machine file's [temperatures]
  bool quiet = false;
};

struct SimulateArgs {
  std::string machine;             // the "true" machine
  std::string input;
  std::string output;              // tool path CSV
  std::string var_file, tool_table, process;
  std::string machine_units = "mm";
  std::string compensation;        // machine file volkins corrects with (none: uncompensated)
  std::string world = "axes";
  double step_mm = 0.5;
  std::vector<int> ball_end_tools;
};

struct MeasureArgs {
  std::string path;                // tool path CSV (volcomp simulate)
  std::string plan;                // CMM plan CSV
  std::string output;              // CMM report CSV
  double noise_um = 0.0;
  double probe_radius_mm = 0.0;
  double flute_length_mm = 30.0;
  unsigned seed = 1;
};

struct SelftuneArgs {
  std::string machine;             // the model (machine file) the program was made for
  std::string input;               // program Pi that machined the measured part
  std::string report;              // CMM report Ri
  std::string report_unit;         // for a CMM export whose file states no unit: mm, um or inch
  std::string deviation_sign;      // of a CMM export's deviation column: actual-minus-nominal or nominal-minus-actual
  bool decimal_comma = false;      // a CMM export writes 12,5
  std::string output;              // program P(i+1)
  std::string strategy = "local";  // local or model
  std::string var_file, tool_table, world = "axes";
  std::string machine_units = "mm";
  bool compensated = false;        // Pi ran with volkins correcting with MACHINE
  std::vector<int> ball_end_tools;
  double flute_length_mm = 30.0;
  double cutoff_mm = 10.0, outlier_sigmas = 4.0;
  // local
  double gain = 1.0, radius_mm = 40.0, angle_deg = 20.0, step_mm = 1.0, tolerance_mm = 0.0005;
  bool no_tilt = false;            // keep the program's tool axis (tip shifted only)
  double min_support = 6.0;        // local: widen the window where fewer points carry a shift
  // model
  std::string tables_out;          // folder of the updated machine file and tables
  std::string nominal;             // the original program P0 (default: PROGRAM)
  std::string next_program, next_points;  // model: another part (program, CMM plan): the noise carried there
  std::vector<std::string> deviations;
  int nodes = 5;
  double regularisation = 1e-3, smoothness = 1e-2;
};

struct PerturbArgs {
  std::string machine;
  std::string folder;
  double low = 0.2, high = 0.5;
  unsigned seed = 1;
  std::vector<std::string> locations;  // "EX0C=15um": only these location errors, changed by these
  std::vector<std::string> add_tables; // error tables the true machine has in addition (each under its columns' axis)
};

int run_perturb(const PerturbArgs& args, std::ostream& report);
int run_selftune(const SelftuneArgs& args, std::ostream& report);
int run_simulate(const SimulateArgs& args, std::ostream& report);
int run_measure(const MeasureArgs& args, std::ostream& report);
int run_predistort(const PredistortArgs& args, std::ostream& report);
int run_check(const CheckArgs& args, std::ostream& out);
int run_balance(const BalanceArgs& args, std::ostream& out);
int run_fit_tables(const FitTablesArgs& args, std::ostream& out);
int run_identify_laser(const IdentifyLaserArgs& args, std::ostream& out);
int run_identify_circle(const IdentifyCircleArgs& args, std::ostream& out);
int run_identify_sphere(const IdentifySphereArgs& args, std::ostream& out);
int run_probe_plan(const ProbePlanArgs& args, std::ostream& out);
int run_plot(const PlotArgs& args, std::ostream& out);
int run_report(const ReportArgs& args, std::ostream& out);
// The patch goes to `patch_out` unless args.patch names a file; the summary to `report`.
int run_init(const InitArgs& args, std::ostream& patch_out, std::ostream& report);
int run_trace(const TraceArgs& args, std::ostream& out);
int run_error(const PoseArgs& args, std::ostream& out);
int run_correct(const PoseArgs& args, std::ostream& out);

}  // namespace vc::cli
