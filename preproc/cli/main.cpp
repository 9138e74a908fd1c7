// volcomp: the command line of the volumetric compensation tools.
#include <CLI/CLI.hpp>
#include <iostream>

#include "commands.hpp"
#include "vc/tables/source_error.hpp"

int main(int argc, char** argv) {
  CLI::App app{"volcomp: volumetric error compensation for CNC machines (machine file + error tables)"};
  app.require_subcommand(1);

  vc::cli::CheckArgs check;
  CLI::App* check_cmd = app.add_subcommand(
      "check", "Validate a machine file and its tables; summarise axes, tables, error and invertibility");
  check_cmd->add_option("MACHINE", check.machine, "machine description file (.toml)")->required();
  check_cmd->add_option("--samples", check.samples, "random poses sampled over the travel")
      ->capture_default_str();
  check_cmd->add_option("--ini", check.ini,
                        "a LinuxCNC configuration that loads this machine with volkins: is every axis inside its "
                        "limits after homing?")
      ->check(CLI::ExistingFile);

  vc::cli::PoseArgs error;
  CLI::App* error_cmd = app.add_subcommand(
      "error", "Volumetric error at each pose: ex,ey,ez (mm, part frame), ekx,eky,ekz (rad)");
  vc::cli::PoseArgs correct;
  CLI::App* correct_cmd = app.add_subcommand(
      "correct", "Corrected joints at each pose: c<axis>..., residual_mm, residual_rad, iterations");
  for (auto [cmd, args] : {std::pair{error_cmd, &error}, std::pair{correct_cmd, &correct}}) {
    cmd->add_option("MACHINE", args->machine, "machine description file (.toml)")->required();
    cmd->add_option("--poses", args->poses, "CSV of nominal poses, header of axis letters (x,y,z,b,c)")
        ->required();
    cmd->add_option("--tool-length", args->tool_length_mm,
                    "L in mm: gauge length + tool length (default: the machine file's tool_length_mm)");
  }
  error_cmd->add_option("--only", error.only,
                        "keep only these deviations, e.g. --only EAX,EC0Y (the others are zero)")
      ->delimiter(',');
  error_cmd->add_flag("--ideal-tip", error.ideal_tip,
                      "also the ideal machine's tool tip, tx,ty,tz (mm, part frame): where each pose puts the tool");

  vc::cli::TraceArgs trace;
  CLI::App* trace_cmd = app.add_subcommand(
      "trace", "Tool-tip error along a recorded LinuxCNC session, and volkins checked against the core");
  trace_cmd->add_option("MACHINE", trace.machine, "machine description file (.toml)")->required();
  trace_cmd->add_option("TRACE", trace.trace, "trace CSV written by the headless driver")->required();
  trace_cmd->add_option("--world", trace.world, "the module's world convention: axes or tcp")->capture_default_str();
  trace_cmd->add_option("-o,--output", trace.output,
                        "write t_s,ex_um,ey_um,ez_um,e_um,ek_urad,gain per sample to this CSV");
  trace_cmd->add_option("--comp-files", trace.comp_files,
                        "a session without correction: also its tool-tip error with these COMP_FILEs (fit-tables' "
                        "joint_N_<axis>.comp) replayed as LinuxCNC applies them");
  trace_cmd->add_option("--replay-output", trace.replay_output, "with --comp-files: write t_s,e_um per sample of the "
                        "replay to this CSV");
  trace_cmd->add_option("--ini", trace.ini, "with --comp-files: the configuration's INI ([JOINT_n] MAX_VELOCITY, "
                        "MAX_ACCELERATION: LinuxCNC's ramp of the correction)");

  vc::cli::PredistortArgs predistort;
  CLI::App* predistort_cmd = app.add_subcommand(
      "predistort", "Write a part program that makes the uncompensated machine cut the nominal part");
  predistort_cmd->add_option("MACHINE", predistort.machine, "machine description file (.toml)")->required();
  predistort_cmd->add_option("PROGRAM", predistort.input, "part program (RS274/NGC)")->required();
  predistort_cmd->add_option("-o,--output", predistort.output, "pre-distorted program, or - for stdout")
      ->required();
  predistort_cmd->add_option("--var", predistort.var_file,
                             "LinuxCNC parameter file (.var): work offsets G54..G59.3, G28/G30 homes");
  predistort_cmd->add_option("--tool-table", predistort.tool_table, "LinuxCNC tool table (.tbl): tool lengths");
  predistort_cmd->add_option("--machine-units", predistort.machine_units,
                         "the unit of the tool table and the .var file, LinuxCNC's [TRAJ]LINEAR_UNITS: mm or inch")
      ->capture_default_str();
  predistort_cmd
      ->add_option("--subroutine-path", predistort.subroutine_path,
                   "folders searched for NAME.ngc when o<name> call or M98 P<n> finds no definition in the program "
                   "(the INI's [RS274NGC]SUBROUTINE_PATH and [DISPLAY]PROGRAM_PREFIX); ':'-separated or repeated")
      ->delimiter(':')
      ->check(CLI::ExistingDirectory);
  predistort_cmd->add_option("--line-map", predistort.line_map,
                             "write output_line,input_file,input_line for every line of the output (CSV): where "
                             "each line of the flat program comes from");
  predistort_cmd->add_option(
      "--start", predistort.start,
      "where the machine is when the program starts, for a program that cuts before it has moved every axis: "
      "X,Y,Z[,A,B,C] (machine coordinates, mm and deg) or the machine's LinuxCNC INI file (its [JOINT_n]HOME, "
      "the position after homing). Without it such a program is refused");
  predistort_cmd->add_option("--process", predistort.process,
                             "cutting conditions per tool (.toml): adds the cutting-force deflection");
  predistort_cmd->add_option("--tolerance", predistort.tolerance_mm,
                             "largest path deviation from the exact correction, mm")
      ->capture_default_str();
  predistort_cmd->add_option("--temperature", predistort.temperatures,
                             "NAME=VALUE: a temperature input of the machine file, degC (repeatable; default: its reference)");
  predistort_cmd->add_option("--tolerance-rad", predistort.tolerance_rad,
                             "largest tool direction deviation from the exact correction between the written points, "
                             "rad (machines with rotary axes)")
      ->capture_default_str();
  predistort_cmd->add_option("--world", predistort.world,
                             "world convention of the machine's kinematics: axes (trivkins) or tcp")
      ->capture_default_str();
  predistort_cmd->add_flag("-q,--quiet", predistort.quiet, "no summary on stderr");

  vc::cli::SimulateArgs simulate;
  CLI::App* simulate_cmd = app.add_subcommand(
      "simulate", "Run a program on a (true) machine and write the actual tool path (part frame)");
  simulate_cmd->add_option("MACHINE", simulate.machine, "the true machine's description file (.toml)")->required();
  simulate_cmd->add_option("PROGRAM", simulate.input, "part program (RS274/NGC)")->required();
  simulate_cmd->add_option("-o,--output", simulate.output, "tool path CSV")->required();
  simulate_cmd->add_option("--var", simulate.var_file, "LinuxCNC parameter file (.var)");
  simulate_cmd->add_option("--tool-table", simulate.tool_table, "LinuxCNC tool table (.tbl): lengths and diameters");
  simulate_cmd->add_option("--machine-units", simulate.machine_units,
                         "the unit of the tool table and the .var file, LinuxCNC's [TRAJ]LINEAR_UNITS: mm or inch")
      ->capture_default_str();
  simulate_cmd->add_option("--process", simulate.process, "cutting conditions per tool (.toml): cutting-force deflection");
  simulate_cmd->add_option("--compensation", simulate.compensation,
                           "machine file the kinematics module corrects with (default: none, uncompensated)");
  simulate_cmd->add_option("--world", simulate.world, "world convention: axes or tcp")->capture_default_str();
  simulate_cmd->add_option("--step", simulate.step_mm, "largest distance between samples, mm")->capture_default_str();
  simulate_cmd->add_option("--ball-end", simulate.ball_end_tools, "tools with a ball end, e.g. --ball-end 2,5")
      ->delimiter(',');

  vc::cli::MeasureArgs measure;
  CLI::App* measure_cmd = app.add_subcommand(
      "measure", "Virtual CMM: measure the surface a tool path machined at the points of a plan");
  measure_cmd->add_option("PATH", measure.path, "tool path CSV (volcomp simulate)")->required();
  measure_cmd->add_option("PLAN", measure.plan, "CMM plan CSV: id,x[mm],y[mm],z[mm],i,j,k")->required();
  measure_cmd->add_option("-o,--output", measure.output, "CMM report CSV")->required();
  measure_cmd->add_option("--noise", measure.noise_um, "gaussian noise (standard deviation), um")->capture_default_str();
  measure_cmd->add_option("--probe-radius", measure.probe_radius_mm, "stylus ball radius, mm")->capture_default_str();
  measure_cmd->add_option("--flute-length", measure.flute_length_mm, "cutting length of the tools, mm")
      ->capture_default_str();
  measure_cmd->add_option("--seed", measure.seed, "seed of the noise")->capture_default_str();

  vc::cli::PerturbArgs perturb;
  CLI::App* perturb_cmd = app.add_subcommand(
      "perturb", "Write a \"true\" machine for the virtual shop: every table off by a smooth 20-50 %");
  perturb_cmd->add_option("MACHINE", perturb.machine, "machine file (.toml)")->required();
  perturb_cmd->add_option("-o,--output", perturb.folder, "folder for the true machine file and its extra tables")
      ->required();
  perturb_cmd->add_option("--low", perturb.low, "smallest relative change")->capture_default_str();
  perturb_cmd->add_option("--high", perturb.high, "largest relative change")->capture_default_str();
  perturb_cmd->add_option("--seed", perturb.seed, "seed of the shapes")->capture_default_str();
  perturb_cmd->add_option("--location", perturb.locations,
                          "change only this location error by this much, tables kept, e.g. --location EX0C=15um "
                          "--location EA0C=-3arcsec (um, mm, arcsec, urad; repeatable)");
  perturb_cmd->add_option("--add-table", perturb.add_tables,
                          "an error table the true machine has in addition to the file's, listed under the axis its "
                          "columns name (repeatable; with or without --location)");

  vc::cli::SelftuneArgs selftune;
  CLI::App* selftune_cmd = app.add_subcommand(
      "selftune", "Program of the next part from the measured deviations of this one (local or model strategy)");
  selftune_cmd->add_option("MACHINE", selftune.machine, "machine file the program was made for (.toml)")->required();
  selftune_cmd->add_option("PROGRAM", selftune.input, "program Pi that machined the measured part")->required();
  selftune_cmd->add_option("REPORT", selftune.report,
                           "CMM report Ri: id,x[mm],y[mm],z[mm],i,j,k,deviation[um], or a CMM software's table "
                           "export (nominal X Y Z, normal I J K out of the material, actual X Y Z or deviation)")
      ->required();
  selftune_cmd->add_option("--report-unit", selftune.report_unit,
                           "CMM export: the unit of the columns whose header names none (mm, um, inch)");
  selftune_cmd->add_option("--deviation-sign", selftune.deviation_sign,
                           "CMM export: what its deviation column is: actual-minus-nominal (+ = material left, along "
                           "an outward normal) or nominal-minus-actual")
      ->check(CLI::IsMember({"actual-minus-nominal", "nominal-minus-actual"}));
  selftune_cmd->add_flag("--decimal-comma", selftune.decimal_comma, "CMM export: numbers are written 12,5");
  selftune_cmd->add_option("-o,--output", selftune.output, "program P(i+1)");
  selftune_cmd->add_option("--strategy", selftune.strategy, "local (shift the path) or model (tune the tables)")
      ->capture_default_str();
  selftune_cmd->add_option("--var", selftune.var_file, "LinuxCNC parameter file (.var)");
  selftune_cmd->add_option("--tool-table", selftune.tool_table, "LinuxCNC tool table (.tbl): lengths and diameters");
  selftune_cmd->add_option("--machine-units", selftune.machine_units,
                         "the unit of the tool table and the .var file, LinuxCNC's [TRAJ]LINEAR_UNITS: mm or inch")
      ->capture_default_str();
  selftune_cmd->add_option("--world", selftune.world, "world convention: axes or tcp")->capture_default_str();
  selftune_cmd->add_flag("--compensated", selftune.compensated,
                         "PROGRAM ran with volkins correcting with MACHINE (not pre-distorted)");
  selftune_cmd->add_option("--ball-end", selftune.ball_end_tools, "tools with a ball end")->delimiter(',');
  selftune_cmd->add_option("--flute-length", selftune.flute_length_mm, "cutting length of the tools, mm")
      ->capture_default_str();
  selftune_cmd->add_option("--cutoff", selftune.cutoff_mm, "shorter wavelengths are not tuned (low-pass), mm")
      ->capture_default_str();
  selftune_cmd->add_option("--outlier-sigmas", selftune.outlier_sigmas, "outlier threshold, robust sigmas")
      ->capture_default_str();
  selftune_cmd->add_option("--gain", selftune.gain, "local: share of the deviation taken off")->capture_default_str();
  selftune_cmd->add_option("--radius", selftune.radius_mm, "local: deviations reach the path within this, mm")
      ->capture_default_str();
  selftune_cmd->add_option("--angle", selftune.angle_deg,
                           "local: deviations reach path points whose tool frame is turned less than this from the cut's, deg")
      ->capture_default_str();
  selftune_cmd->add_option("--min-support", selftune.min_support,
                           "local: where fewer measured points than this carry a shift, widen its window (radius and angle x 1.5, up to 3 times); 0: never")
      ->capture_default_str();
  selftune_cmd->add_flag("--no-tilt", selftune.no_tilt, "local: keep the program's tool axis on 5-axis moves (shift the tip only)");
  selftune_cmd->add_option("--step", selftune.step_mm, "local: longest piece of a shifted move, mm")->capture_default_str();
  selftune_cmd->add_option("--tolerance", selftune.tolerance_mm, "chord and blending tolerance, mm")->capture_default_str();
  selftune_cmd->add_option("--tables-out", selftune.tables_out, "model: folder for the updated machine file and tables");
  selftune_cmd->add_option("--nominal", selftune.nominal, "model: the original program P0 (default: PROGRAM)");
  selftune_cmd->add_option("--next-program", selftune.next_program,
                           "model: the program of another part (with --next-points): the noise the tuned tables carry to its points");
  selftune_cmd->add_option("--next-points", selftune.next_points, "model: that part's CMM plan (id,x,y,z,i,j,k)");
  selftune_cmd->add_option("--deviations", selftune.deviations, "model: deviations to tune, e.g. EXX,EX0C (default: every table and the rotary axes' locations)")
      ->delimiter(',');
  selftune_cmd->add_option("--nodes", selftune.nodes, "model: table nodes over each axis's travel (a full turn: a Fourier series of order (nodes - 1) / 2)")->capture_default_str();
  selftune_cmd->add_option("--regularisation", selftune.regularisation, "model: ridge on scaled unknowns")
      ->capture_default_str();
  selftune_cmd->add_option("--smoothness", selftune.smoothness, "model: penalty on second differences")
      ->capture_default_str();

  vc::cli::BalanceArgs balance;
  CLI::App* balance_cmd = app.add_subcommand(
      "balance", "Accuracy balance: each deviation's effect at the tool tip over the travel, largest first "
                 "(what to measure first)");
  balance_cmd->add_option("MACHINE", balance.machine, "machine description file (.toml)")->required();
  balance_cmd->add_option("--levels", balance.levels, "positions per joint over its travel (2..21)")->capture_default_str();
  balance_cmd->add_option("--tool-length", balance.tool_length_mm, "tool length L, mm (default: the machine file's)");
  balance_cmd->add_option("-o,--output", balance.output, "CSV: deviation, M, delta, RMS (um), share (%), direction (urad)");
  balance_cmd->add_option("--plot", balance.plot, "bar chart, .png or .svg (gnuplot); the data it draws goes to a .csv beside it");

  vc::cli::PlotArgs plot;
  CLI::App* plot_cmd = app.add_subcommand(
      "plot", "Draw a machine file's errors: per axis its component errors against its position (PNG or SVG with "
              "the data as CSV), and the location errors listed with units");
  plot_cmd->add_option("MACHINE", plot.machine, "machine description file (.toml)")->required();
  plot_cmd->add_option("-o,--output", plot.folder, "folder for <axis>_axis.png and .csv and location_errors.csv")
      ->required();
  plot_cmd->add_option("--format", plot.format, "png or svg")->capture_default_str();
  plot_cmd->add_flag("--volume", plot.volume,
                     "also the volume map: the tool-tip error |e| (um) over X-Y at three Z levels, rotary axes at 0 "
                     "and at their worst, before correction and with LinuxCNC's tables (usual practice, modified method)");
  plot_cmd->add_option("--tool-lengths", plot.tool_lengths_mm, "the volume map's tool lengths, mm, e.g. 0,100 "
                       "(default: the machine file's)")->delimiter(',');
  plot_cmd->add_option("--plane", plot.plane, "the volume map's plane, two linear axes, e.g. xz or yz, the third "
                       "giving the levels (default: the first two, X-Y)");
  plot_cmd->add_option("--controller", plot.controller, "the stock controller whose tables the volume map judges "
                       "(as fit-tables --controller), or none")->capture_default_str();

  vc::cli::ReportArgs report;
  CLI::App* report_cmd = app.add_subcommand(
      "report", "One self-contained HTML page of the machine's accuracy: its file and checksums, tables, location "
                "errors, accuracy balance, volume map, and the laser runs and circular tests of --measurements");
  report_cmd->add_option("MACHINE", report.machine, "machine description file (.toml)")->required();
  report_cmd->add_option("--measurements", report.measurements,
                         "folder of laser runs (ISO 230-2) and circular tests (ISO 230-4), CSV (preproc/report/README.md)");
  report_cmd->add_option("-o,--output", report.output, "the HTML page to write")->required();
  report_cmd->add_option("--tool-lengths", report.tool_lengths_mm, "the volume map's tool lengths, mm (default: 0 and "
                         "the machine file's)")->delimiter(',');

  vc::cli::FitTablesArgs fit_tables;
  CLI::App* fit_tables_cmd = app.add_subcommand(
      "fit-tables", "A stock controller's compensation tables by the source's modified method: all tables fitted "
                    "together to the whole model; M and Delta of none, usual practice, fit and full correction");
  fit_tables_cmd->add_option("MACHINE", fit_tables.machine, "machine description file (.toml)")->required();
  fit_tables_cmd->add_option("--controller", fit_tables.controller,
                             "the controller's tables: linuxcnc, source14, or a controller file (.toml)")->required();
  fit_tables_cmd->add_option("-o,--output", fit_tables.output,
                             "folder for report.csv, tables.csv and the controller's own files (LinuxCNC: COMP_FILEs "
                             "and the INI lines)")
      ->required();
  fit_tables_cmd->add_option("--criterion", fit_tables.criterion, "minimax (smallest M) or ls (least squares)")
      ->capture_default_str();
  fit_tables_cmd->add_option("--tool-lengths", fit_tables.tool_lengths,
                             "tool lengths L fitted together, mm, e.g. 0,100,200 (default: the machine file's)")
      ->delimiter(',');
  fit_tables_cmd->add_option("--check-tool-lengths", fit_tables.check_tool_lengths,
                             "tool lengths judged but not fitted, mm (default: the fitted ones' midpoints and largest + 50)")
      ->delimiter(',');
  fit_tables_cmd->add_option("--rotary", fit_tables.rotary,
                             "rotary grid positions, deg, e.g. --rotary B=-90,-60,-30,0,30 (repeatable; default: --levels "
                             "positions over the travel)");
  fit_tables_cmd->add_option("--nodes", fit_tables.nodes, "nodes per table, equally spaced over the travel (default: the controller's)");
  fit_tables_cmd->add_option("--levels", fit_tables.levels, "grid positions per joint (default: the nodes)");
  fit_tables_cmd->add_option("--fresh", fit_tables.fresh, "random poses per tool length in each fresh set (refit, check)")
      ->capture_default_str();
  fit_tables_cmd->add_option("--ridge", fit_tables.ridge,
                             "regularisation towards the usual practice, relative to each table's tip effect")
      ->capture_default_str();
  fit_tables_cmd->add_option("--smoothness", fit_tables.smoothness,
                             "regularisation of the second differences of the departure from the usual practice")
      ->capture_default_str();
  fit_tables_cmd->add_option("--programs", fit_tables.programs,
                             "part programs (G-code, as the stock machine runs them: no TCP) whose poses are fitted "
                             "with the grid and judged as the set 'programs'")
      ->check(CLI::ExistingFile);
  fit_tables_cmd->add_flag("--programs-only", fit_tables.programs_only,
                           "fit the programs' poses alone: best for those parts, the volume only judged");
  fit_tables_cmd->add_option("--tool-table", fit_tables.tool_table, "LinuxCNC tool table the programs are read with");
  fit_tables_cmd->add_option("--var", fit_tables.var_file, "LinuxCNC parameter file (.var) the programs are read with");
  fit_tables_cmd->add_option("--machine-units", fit_tables.machine_units, "mm or inch: LinuxCNC's [TRAJ]LINEAR_UNITS");
  fit_tables_cmd->add_option("--reversal", fit_tables.reversal,
                             "AXIS=RUNS.csv: laser runs of that axis in both directions (identify laser's format); "
                             "its COMP_FILE's forward and reverse columns take their reversal B (LinuxCNC only; repeatable)");

  CLI::App* identify_cmd = app.add_subcommand("identify", "From measurements to the machine file")->require_subcommand(1);
  vc::cli::IdentifyLaserArgs laser;
  CLI::App* laser_cmd = identify_cmd->add_subcommand(
      "laser", "Laser interferometer runs (ISO 230-2): evaluation, suspicious runs, the error table");
  laser_cmd->add_option("RUNS", laser.runs, "runs CSV: target[mm],run,direction,deviation[um] or target[mm],1+[um],1-[um],...")
      ->required();
  laser_cmd->add_option("--error", laser.error, "the component error the runs measure: EXX, EYX, EAX, ECC, ...")->required();
  laser_cmd->add_option("-o,--output", laser.output, "error table CSV in the project's format");
  laser_cmd->add_option("--direction", laser.direction, "the table's value: both (mean bidirectional), up or down")
      ->capture_default_str();
  laser_cmd->add_flag("--keep-all", laser.keep_all, "keep the suspicious runs in the evaluation");
  laser_cmd->add_option("--machine", laser.machine, "machine file whose axis takes the identified table");
  laser_cmd->add_option("--machine-out", laser.machine_out,
                        "folder: the table and a copy of the machine file with it in place of the error's old values");
  laser_cmd->add_option("--at", laser.at,
                        "where every axis stood during the runs, e.g. x=0,y=-160,z=-150,b=0,c=0 (default: the runs' '# at:')");
  laser_cmd->add_option("--tool-length", laser.tool_length_mm,
                        "the tool-side optic's distance below the spindle gauge point, mm (default: the runs' "
                        "'# tool_length_mm:')");
  laser_cmd->add_option("--tool-point", laser.tool_point_mm,
                        "the tool-side optic in the spindle frame from the gauge point, X,Y,Z mm (the runs' "
                        "'# tool_point_mm:'); a tool's tip L long is 0,0,-L")
      ->delimiter(',')
      ->expected(3);
  laser_cmd->add_option("--reference", laser.reference,
                        "none: the readings as they are (positioning, angular: the default); datum: the laser zeroed "
                        "at the first target, the file keeps its value there; least-squares (a straightness's default) "
                        "or end-points: the straightness about that line, its slope a squareness")
      ->check(CLI::IsMember({"datum", "least-squares", "end-points", "none"}));
  laser_cmd->add_option("--squareness", laser.squareness,
                        "the location error that takes a straightness's slope, e.g. EC0X or EC0Y for EYX (default: the "
                        "one the file uses, else the measured axis's own)");
  laser_cmd->add_option("--plot", laser.plot,
                        "the ISO 230-2 graph, .png or .svg (gnuplot); the data it draws goes to a .csv beside it");
  vc::cli::IdentifyCircleArgs circle;
  CLI::App* circle_cmd = identify_cmd->add_subcommand(
      "circle", "Circular test / ballbar (ISO 230-4): G, H, centre, squareness, scale mismatch, reversal spikes");
  circle_cmd->add_option("RUN", circle.run, "CSV: angle[deg],direction,deviation[um] or angle[deg],ccw[um],cw[um]")->required();
  circle_cmd->add_option("--plane", circle.plane, "XY, YZ or ZX (default: the file's '# plane:')");
  circle_cmd->add_option("--radius", circle.radius_mm, "the circle's radius, mm (default: the file's '# radius_mm:')");
  circle_cmd->add_option("--machine", circle.machine, "machine file: the squareness in its location errors");
  circle_cmd->add_option("--machine-out", circle.machine_out, "folder: a copy of the machine file with the squareness set");
  circle_cmd->add_option("--symbol", circle.symbol, "the location error that takes it (default: the one the file uses)");
  circle_cmd->add_option("--plot", circle.plot,
                         "the ballbar polar plot, .png or .svg (gnuplot); the data it draws goes to a .csv beside it");
  vc::cli::IdentifySphereArgs sphere;
  CLI::App* sphere_cmd = identify_cmd->add_subcommand(
      "sphere", "Rotary axes' location errors from a sphere's centre probed at several rotary positions");
  sphere_cmd->add_option("MACHINE", sphere.machine, "machine description file (.toml)")->required();
  sphere_cmd->add_option("CENTRES", sphere.centres, "probe-plan log, or a CSV of the joints at the sphere's centre per pose (x,y,z,b,c)")->required();
  sphere_cmd->add_option("--deviations", sphere.deviations, "location errors to identify, e.g. EX0C,EA0B (default: all)")
      ->delimiter(',');
  sphere_cmd->add_option("--tool-length", sphere.tool_length_mm, "probe length L, mm (default: the machine file's)");
  sphere_cmd->add_option("--machine-out", sphere.machine_out, "folder: a copy of the machine file with the values");

  vc::cli::ProbePlanArgs plan;
  CLI::App* plan_cmd = app.add_subcommand(
      "probe-plan", "A LinuxCNC program that probes a sphere at rotary positions for 'identify sphere' (G38.2, LOG)");
  plan_cmd->add_option("MACHINE", plan.machine, "machine description file (.toml)")->required();
  plan_cmd->add_option("--centre", plan.centre, "X,Y,Z: the sphere's centre at rotary 0, as the DRO shows it (mm)")
      ->delimiter(',')->required();
  plan_cmd->add_option("--sphere-diameter", plan.sphere_diameter_mm, "mm")->capture_default_str();
  plan_cmd->add_option("--ball-diameter", plan.ball_diameter_mm, "the stylus ball, mm")->capture_default_str();
  plan_cmd->add_option("--probe-length", plan.probe_length_mm, "gauge point to ball centre, mm (default: the machine file's)");
  plan_cmd->add_option("--grid", plan.grid, "rotary positions, e.g. --grid B=0,-30,-60,-90 --grid C=0,90,180,270")->required();
  plan_cmd->add_option("--clearance", plan.clearance_mm, "the search starts this far off the surface, mm")
      ->capture_default_str();
  plan_cmd->add_option("--probe-feed", plan.probe_feed_mm_min, "the search for the surface, mm/min")->capture_default_str();
  plan_cmd->add_option("--back-off", plan.back_off_mm, "back-off after the search, mm")->capture_default_str();
  plan_cmd->add_option("--touch-feed", plan.touch_feed_mm_min,
                       "the measuring touch, mm/min (its trip is logged: LinuxCNC latches it up to feed x servo period late)")
      ->capture_default_str();
  plan_cmd->add_option("--log", plan.log_file, "the log file LinuxCNC writes (LOGOPEN)")->capture_default_str();
  plan_cmd->add_option("-o,--output", plan.output, "the program (default: stdout)");

  vc::cli::InitArgs init;
  CLI::App* init_cmd = app.add_subcommand(
      "init", "From a LinuxCNC configuration: a machine file with its kinematics' nominal geometry (zero errors) "
              "and the patch that loads volkins in place of the stock module (summary on stderr)");
  init_cmd->add_option("CONFIG", init.ini, "the configuration's INI file")->required();
  init_cmd->add_option("-o,--output", init.output, "the machine file to write (.toml)")->required();
  init_cmd->add_option("--patch", init.patch,
                       "write the patch (unified diff, for patch -p1 -d CONFIG_DIR) to this file; - or none: stdout");

  CLI11_PARSE(app, argc, argv);
  try {
    if (*check_cmd) return vc::cli::run_check(check, std::cout);
    if (*balance_cmd) return vc::cli::run_balance(balance, std::cout);
    if (*plot_cmd) return vc::cli::run_plot(plot, std::cout);
    if (*report_cmd) return vc::cli::run_report(report, std::cout);
    if (*fit_tables_cmd) return vc::cli::run_fit_tables(fit_tables, std::cout);
    if (*laser_cmd) return vc::cli::run_identify_laser(laser, std::cout);
    if (*circle_cmd) return vc::cli::run_identify_circle(circle, std::cout);
    if (*sphere_cmd) return vc::cli::run_identify_sphere(sphere, std::cout);
    if (*plan_cmd) return vc::cli::run_probe_plan(plan, std::cout);
    if (*init_cmd) return vc::cli::run_init(init, std::cout, std::cerr);
    if (*error_cmd) return vc::cli::run_error(error, std::cout);
    if (*correct_cmd) return vc::cli::run_correct(correct, std::cout);
    if (*trace_cmd) return vc::cli::run_trace(trace, std::cout);
    if (*predistort_cmd) return vc::cli::run_predistort(predistort, std::cerr);
    if (*simulate_cmd) return vc::cli::run_simulate(simulate, std::cerr);
    if (*measure_cmd) return vc::cli::run_measure(measure, std::cerr);
    if (*perturb_cmd) return vc::cli::run_perturb(perturb, std::cerr);
    if (*selftune_cmd) return vc::cli::run_selftune(selftune, std::cerr);
  } catch (const std::exception& e) {
    std::cout.flush();
    std::cerr << e.what() << '\n';
    return 2;
  }
  return 0;
}
