// CMM reports as CMM software exports them (vc/shop/cmm_export.hpp): every layout the reader
// takes (separators, column order and spellings, units in the header, on a units line or
// given, inch, decimal comma, deviation or actual point, the sign), and the refusals, each
// with file:line:column and its reason.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "vc/shop/cmm.hpp"
#include "vc/shop/cmm_export.hpp"
#include "vc/tables/source_error.hpp"

namespace vc {
namespace {

namespace fs = std::filesystem;
using shop::DeviationSign;
using shop::ReportFormat;

constexpr double kInch = 25.4;

class CmmExport : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("vc_cmm_export_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& text, const std::string& name = "report.csv") {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
  std::vector<shop::CmmPoint> read(const std::string& text, const ReportFormat& format = {}, bool report = true) {
    layout_.clear();
    return shop::read_cmm_points(write(text), report, format, &layout_);
  }
  // The file is refused with a vc::LoadError at `where` ("line:column") whose text holds `what`.
  void refused(const std::string& text, const ReportFormat& format, const std::string& where, const std::string& what) {
    const std::string path = write(text, "bad.csv");
    try {
      shop::read_cmm_points(path, true, format);
      ADD_FAILURE() << "accepted:\n" << text;
    } catch (const LoadError& e) {
      const std::string at = where.empty() ? path + ": error: " : path + ":" + where + ": error: ";
      EXPECT_NE(std::string(e.what()).find(at), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  }
  static ReportFormat sign(DeviationSign s, const std::string& unit = "") {
    ReportFormat f;
    f.sign = s;
    f.unit = unit;
    return f;
  }
  fs::path dir_;
  std::string layout_;
};

TEST_F(CmmExport, SemicolonsDecimalCommasAndAUnitsLineInInches) {
  // A preamble, the unit on its own line, quoted names, tolerances that are not used.
  ReportFormat format = sign(DeviationSign::ActualMinusNominal);
  format.decimal_comma = true;
  const auto p = read(
      "Part: bracket 4711;;\nUnits: inch\n\n"
      "Point Name;X Nom;Y Nom;Z Nom;I;J;K;X Act;Y Act;Z Act;Dev;+Tol;-Tol\n"
      "\"PT 1\";1,0000;2,0000;3,0000;0;0;1;1,0000;2,0000;3,0010;0,0010;0,002;-0,002\n"
      "\"PT 2\";-1,5;0;0;-1;0;0;-1,5020;0,0003;0;0,0020;0,002;-0,002\n",
      format);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0].id, "PT 1");
  EXPECT_EQ(p[0].line, 5);
  EXPECT_NEAR(p[0].nominal.z(), 3 * kInch, 1e-12);
  EXPECT_NEAR(*p[0].deviation_mm, 0.001 * kInch, 1e-12);
  // Outward normal -X, actual further along it: material left, +.
  EXPECT_NEAR(p[1].nominal.x(), -1.5 * kInch, 1e-12);
  EXPECT_NEAR(*p[1].deviation_mm, 0.002 * kInch, 1e-12);
  EXPECT_NE(layout_.find("semicolon-separated, header on line 4"), std::string::npos) << layout_;
  EXPECT_NE(layout_.find("'X Act','Y Act','Z Act' [inch]"), std::string::npos) << layout_;
  EXPECT_NE(layout_.find("checked against 'Dev'"), std::string::npos) << layout_;
}

TEST_F(CmmExport, TabsUnitsInTheHeaderAndTheDeviationWithItsStatedSign) {
  const std::string text =
      "Name\tNominal X [mm]\tNominal Y [mm]\tNominal Z [mm]\tNormal X\tNormal Y\tNormal Z\tDeviation [um]\n"
      "P1\t1\t2\t3\t0.6\t0.8\t0\t-4.5\n";
  const auto a = read(text, sign(DeviationSign::ActualMinusNominal));
  EXPECT_NEAR(*a.at(0).deviation_mm, -0.0045, 1e-15);
  EXPECT_NEAR(a.at(0).normal.y(), 0.8, 1e-15);
  const auto b = read(text, sign(DeviationSign::NominalMinusActual));
  EXPECT_NEAR(*b.at(0).deviation_mm, 0.0045, 1e-15);
  EXPECT_NE(layout_.find("deviation 'Deviation [um]' [um] as nominal - actual"), std::string::npos) << layout_;
  // Tabs with decimal commas, a unit given for the whole file.
  ReportFormat format = sign(DeviationSign::ActualMinusNominal, "um");
  format.decimal_comma = true;
  const auto c = read("X\tY\tZ\tI\tJ\tK\tDev\n1000,5\t0\t0\t1\t0\t0\t-2,5\n", format);
  EXPECT_NEAR(c.at(0).nominal.x(), 1.0005, 1e-15);
  EXPECT_NEAR(*c.at(0).deviation_mm, -0.0025, 1e-15);
  EXPECT_NE(layout_.find("tab-separated"), std::string::npos) << layout_;
}

TEST_F(CmmExport, ColumnsInAnyOrderWithTheCommonSpellings) {
  // Bare X, Y, Z are the nominal; the deviation comes from the actual point, no sign needed.
  const auto a =
      read("Meas Z,K,ID,X,J,Meas X,Z,I,Y,Meas Y\n7.002,1,A,5,0,5,7,0,6,6\n", sign(DeviationSign::Unstated, "mm"));
  EXPECT_EQ(a.at(0).id, "A");
  EXPECT_EQ(a.at(0).nominal, Eigen::Vector3d(5, 6, 7));
  EXPECT_NEAR(*a.at(0).deviation_mm, 0.002, 1e-12);
  // NX beside I, J, K is the nominal; MX the measured point.
  const auto b = read("NX,NY,NZ,I,J,K,MX,MY,MZ\n1,2,3,0,-1,0,1,1.997,3\n", sign(DeviationSign::Unstated, "mm"));
  EXPECT_EQ(b.at(0).nominal, Eigen::Vector3d(1, 2, 3));
  EXPECT_NEAR(*b.at(0).deviation_mm, 0.003, 1e-12);
  // NX beside a nominal X is the normal; X_Nom, XACT, "Theo", a unit as a word, µm.
  const auto c = read("X_Theo mm,Y_Theo mm,Z_Theo mm,NX,NY,NZ,Dev \xC2\xB5m\n1,2,3,0,0,1,2.5\n",
                      sign(DeviationSign::ActualMinusNominal));
  EXPECT_EQ(c.at(0).normal, Eigen::Vector3d(0, 0, 1));
  EXPECT_NEAR(*c.at(0).deviation_mm, 0.0025, 1e-15);
  EXPECT_EQ(c.at(0).id, "line2");  // no name column: the line
  const auto d = read("XNOM;YNOM;ZNOM;VEC I;VEC J;VEC K;XACT;YACT;ZACT\n0;0;0;1;0;0;-0.01;0;0\n",
                      sign(DeviationSign::Unstated, "mm"));
  EXPECT_NEAR(*d.at(0).deviation_mm, -0.01, 1e-15);
  // A deviation vector.
  const auto e = read("X,Y,Z,I,J,K,Dev X,Dev Y,Dev Z\n0,0,0,0.6,0.8,0,0.001,0.002,0.5\n",
                      sign(DeviationSign::ActualMinusNominal, "mm"));
  EXPECT_NEAR(*e.at(0).deviation_mm, 0.6 * 0.001 + 0.8 * 0.002, 1e-15);
}

TEST_F(CmmExport, AStatedSignIsCheckedAgainstTheActualPointToTheDigitsWritten) {
  const std::string text =
      "Units=MM\nX Nom,Y Nom,Z Nom,I,J,K,X Meas,Y Meas,Z Meas,Dev\n"
      "0,0,0,0.7071,0.7071,0,0.0007,0.0007,0,0.0010\n";
  // sqrt(2) * 0.0007 = 0.00099: within the rounding of the digits written.
  EXPECT_NEAR(*read(text, sign(DeviationSign::ActualMinusNominal)).at(0).deviation_mm, 0.0007 * 1.4142, 1e-7);
  refused(text, sign(DeviationSign::NominalMinusActual), "3:39", "is the opposite of the actual point's");
  refused("Units=MM\nX Nom,Y Nom,Z Nom,I,J,K,X Meas,Y Meas,Z Meas,Dev\n0,0,0,0,0,1,0,0,0.004,0.002\n",
          sign(DeviationSign::ActualMinusNominal), "3:23", "disagrees with the actual point's");
}

TEST_F(CmmExport, PlansNeedOnlyTheNominalAndTheNormal) {
  const auto p = read("Units: mm\nPoint,X,Y,Z,I,J,K\nP1,1,2,3,0,0,1\n", {}, false);
  EXPECT_FALSE(p.at(0).deviation_mm);
  EXPECT_EQ(p.at(0).nominal, Eigen::Vector3d(1, 2, 3));
}

TEST_F(CmmExport, OurCsvIsStillOursAndTakesNoExportOptions) {
  const auto p = read("# ours\nid,x[mm],y[mm],z[mm],i,j,k,deviation[um]\nA,1,2,3,0,0,1,4\n");
  EXPECT_EQ(layout_, "volcomp's CSV");
  EXPECT_NEAR(*p.at(0).deviation_mm, 0.004, 1e-15);
  EXPECT_NO_THROW(
      read("id,x[mm],y[mm],z[mm],i,j,k,deviation[um]\nA,1,2,3,0,0,1,4\n", sign(DeviationSign::ActualMinusNominal)));
  EXPECT_THROW(
      read("id,x[mm],y[mm],z[mm],i,j,k,deviation[um]\nA,1,2,3,0,0,1,4\n", sign(DeviationSign::Unstated, "inch")),
      std::runtime_error);
}

TEST_F(CmmExport, AmbiguousOrIncompleteFilesAreRefusedWithTheWayOut) {
  const ReportFormat none;
  const ReportFormat mm = sign(DeviationSign::Unstated, "mm");
  const ReportFormat stated = sign(DeviationSign::ActualMinusNominal, "mm");
  // Units: none anywhere; two sources that disagree; a unit that is not a length.
  refused("X Nom,Y Nom,Z Nom,I,J,K,X Act,Y Act,Z Act\n0,0,0,0,0,1,0,0,0\n", none, "1:1",
          "no unit for 'X Nom': write it in the header");
  refused("Units: inch\nX Nom,Y Nom,Z Nom,I,J,K,X Act,Y Act,Z Act\n0,0,0,0,0,1,0,0,0\n", mm, "1:1",
          "this units line says inch, --report-unit says mm");
  refused("Units: mm\nX Nom,Y Nom [in],Z Nom,I,J,K,X Act,Y Act,Z Act\n0,0,0,0,0,1,0,0,0\n", none, "2:7",
          "the header says inch, the units line (line 1) says mm");
  refused("X [deg],Y,Z,I,J,K,Dev\n", mm, "1:1", "'deg' is not a length unit");
  refused("Units: mm\nUnits: inch\nX,Y,Z,I,J,K,Dev\n", stated, "2",
          "this units line says inch, the one on line 1 says mm");
  ReportFormat comma = stated;
  comma.decimal_comma = true;
  refused("X,Y,Z,I,J,K,Dev\n0,0,0,0,0,1,0\n", comma, "1", "--decimal-comma, but the header is separated by commas");
  refused("X;Y;Z;I;J;K;Dev\n0;0;0.5;0;0;1;0\n", comma, "2:5", "'0.5' has a decimal point, but --decimal-comma");
  // The sign of a deviation column, when it is what the deviation comes from.
  refused("X,Y,Z,I,J,K,Dev\n0,0,0,0,0,1,0.001\n", mm, "1:13", "the sign of 'Dev' is not stated: give --deviation-sign");
  // Which column is what.
  refused("NX,NY,NZ,MX,MY,MZ\n0,0,0,0,0,0\n", mm, "1:1", "'NX' may be the nominal X or the normal's I");
  refused("Nominal X,Nominal Y,Nominal Z,X,Y,Z,I,J,K\n", mm, "1:31", "'X' is not marked nominal or actual");
  refused("X,Y,Z,I,J,K,Meas X,Meas Y,Meas Z,X Act\n", mm, "1:34",
          "'X Act' is the actual X, and so is 'Meas X' (column 13)");
  refused("X,Y,Z,I,J,Meas X,Meas Y,Meas Z,Vektor K\n", mm, "1", "no column for the normal's K");
  refused("X,Y,Z,I,J,K,Meas X,Meas Z\n", mm, "1", "the actual point has no Y column");
  refused("X,Y,Z,I,J,K,Tol\n0,0,0,0,0,1,0.1\n", stated, "1", "a report needs the actual X, Y, Z or the deviation");
  refused("Feature,Axis,Nominal,Measured,Dev\nPNT1,X,1,1.001,0.001\n", stated, "1", "one row per axis");
  refused("Inspection of part 12\n", stated, "", "no header naming the nominal X, Y and Z");
  // Rows.
  refused("X;Y;Z;I;J;K;Dev\n0;0;0;0;0;1;0,001\n", stated, "2:13", "'0,001' has a comma: give --decimal-comma");
  refused("X,Y,Z,I,J,K,Dev\n0,0,0,0,0,2,0.001\n", stated, "2:7", "the normal (I, J, K) is not a unit vector");
  refused("X,Y,Z,I,J,K,Dev\n0,0,0,0,0,1\n", stated, "2", "6 cells, the header (line 1) has 7");
  refused("Name,X,Y,Z,I,J,K,Dev\n\"P1,0,0,0,0,0,1,0\n", stated, "2:1", "this quote is not closed");
  refused("X,Y,Z,I,J,K,Dev\n0,0,0,0,0,1,abc\n", stated, "2:13", "'abc' is not a number");
  refused("X,Y,Z,I,J,K,Dev\n", stated, "", "no points below the header (line 1)");
}

}  // namespace
}  // namespace vc
