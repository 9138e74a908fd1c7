// The compensation types switched on and off (vc/machine/term_types.hpp): the servo thread's way,
// each term scaled by its type's gain in Conditions, against a model in which the terms of the
// other types are zero (keep_only, by symbol), the terms sorted here from their ISO 230-1 names
// (not by the code under test). On every shipped machine, each basic type alone and mixes, the
// real pose and its derivatives and the whole correction.
#include "vc/machine/term_types.hpp"

#include <gtest/gtest.h>

#include "test_support.hpp"
#include "types_by_name.hpp"
#include "vc/machine/correct.hpp"
#include "vc/machine/deviations.hpp"
#include "vc/machine/forward.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/machine/travel_samples.hpp"

namespace vc {
namespace {

using machine::BasicType;
using machine::Model;
using machine::TypeSelection;
using test::kBasicCodes;
using test::with_only;

TypeSelection selection_of(const std::set<std::string>& types) {
  std::string list = "FOR,thermal";
  for (const std::string& t : types) list += "," + t;
  return machine::parse_type_selection(list);
}

std::vector<std::set<std::string>> selections() {
  std::vector<std::set<std::string>> out;
  for (const char* code : kBasicCodes) out.push_back({code});
  out.push_back({"L-POS", "R-POS"});                                               // the TR's indirect measurement
  out.push_back({"L-POS", "L-STR", "L-SQU", "L-ANG", "R-POS", "R-RAX", "R-ANG"});  // R-POR measured
  out.push_back({"L-POS", "L-SPEC"});  // a cross-axis table with its column's type
  return out;
}

std::vector<std::string> machines_tested() {
  std::vector<std::string> names = test::shipped_machines();
  names.push_back("mc300_thermal");
  return names;
}

// Calls `check(model, switched, only)` for every machine tested and every selection: the
// machine, its conditions with the selection applied, and the model with only those terms.
template <class Check>
void for_every_selection(const Check& check) {
  for (const std::string& name : machines_tested()) {
    const Model model = machine::load_machine(test::machine_path(name));
    for (const auto& types : selections()) {
      SCOPED_TRACE(name + ": " + selection_of(types).to_string());
      machine::Conditions switched = model.reference_conditions();
      machine::apply_selection(model, selection_of(types), switched);
      check(model, switched, with_only(model, types));
    }
  }
}

TEST(TermTypes, EachTypeAloneIsTheModelWithOnlyItsTerms) {
  int compared = 0;
  for_every_selection([&](const Model& model, const machine::Conditions& switched, const Model& only) {
    const machine::Conditions reference = only.reference_conditions();
    machine::TravelSamples samples(model);
    double worst_tip = 0.0, worst_direction = 0.0, worst_rate = 0.0;
    for (int i = 0; i < 100; ++i) {
      const machine::Joints q = samples.next();
      const double L = samples.uniform(0.0, 250.0);
      machine::PoseDerivatives d_switched, d_only;
      const auto a = machine::tool_pose(model, switched, machine::Machine::Real, q, L, d_switched);
      const auto b = machine::tool_pose(only, reference, machine::Machine::Real, q, L, d_only);
      const auto c = machine::tool_pose(model, switched, machine::Machine::Real, q, L);  // the carried pose
      worst_tip = std::max({worst_tip, (a.tip_mm - b.tip_mm).norm(), (c.tip_mm - b.tip_mm).norm()});
      worst_direction =
          std::max({worst_direction, (a.direction - b.direction).norm(), (c.direction - b.direction).norm()});
      // tool_pose fills the machine's joints' columns; the others are not written.
      const Eigen::Index n = model.joint_count();
      worst_rate = std::max({worst_rate, (d_switched.tip - d_only.tip).leftCols(n).cwiseAbs().maxCoeff(),
                             (d_switched.direction - d_only.direction).leftCols(n).cwiseAbs().maxCoeff()});
      ++compared;
    }
    EXPECT_LT(worst_tip, 1e-11);
    EXPECT_LT(worst_direction, 1e-14);
    EXPECT_LT(worst_rate, 1e-13);
  });
  EXPECT_EQ(compared, 5 * 13 * 100);
}

TEST(TermTypes, TheCorrectionWithSomeTypesIsTheCorrectionOfTheirModel) {
  for_every_selection([](const Model& model, const machine::Conditions& switched, const Model& only) {
    machine::TravelSamples samples(model);
    double worst = 0.0;
    for (int i = 0; i < 50; ++i) {
      const machine::Joints q = samples.next();
      const auto a = machine::correct(model, switched, q, model.tool_length_mm);
      const auto b = machine::correct(only, only.reference_conditions(), q, model.tool_length_mm);
      ASSERT_EQ(a.status, b.status);
      worst = std::max(worst, (a.joints - b.joints).cwiseAbs().maxCoeff());
    }
    EXPECT_LT(worst, 1e-9);
  });
}

// A selection that is all of them is the machine as its file holds it, bit for bit.
TEST(TermTypes, EverythingOnIsTheFileItself) {
  const Model model = machine::load_machine(test::machine_path("mc300"));
  machine::Conditions all = model.reference_conditions();
  machine::apply_selection(model, TypeSelection::all(), all);
  EXPECT_TRUE(all.all_types_on());
  machine::TravelSamples samples(model);
  for (int i = 0; i < 20; ++i) {
    const machine::Joints q = samples.next();
    EXPECT_EQ(machine::correct(model, all, q, 100.0).joints, machine::correct(model, q, 100.0).joints);
  }
}

// FOR off: the tool position alone, as at the pole: the rotary joints stay nominal, the tip is
// where the ideal machine puts it, the direction error is the machine's.
TEST(TermTypes, WithoutForTheRotaryJointsAreNotCorrected) {
  for (const std::string name : {"mc300", "ac_trunnion"}) {
    const Model model = machine::load_machine(test::machine_path(name));
    machine::Conditions position_only = model.reference_conditions();
    TypeSelection s = TypeSelection::all();
    s.orientation = false;
    machine::apply_selection(model, s, position_only);
    machine::TravelSamples samples(model);
    double moved = 0.0, tip = 0.0, direction = 0.0;
    for (int i = 0; i < 50; ++i) {
      const machine::Joints q = samples.next();
      const auto c = machine::correct(model, position_only, q, 150.0);
      ASSERT_EQ(c.status, machine::Status::Ok);
      for (int j = 0; j < model.joint_count(); ++j)
        if (model.axes[static_cast<std::size_t>(j)].type == machine::AxisType::Rotary)
          moved = std::max(moved, std::abs(c.joints[j] - q[j]));
      const auto real = machine::tool_pose(model, machine::Machine::Real, c.joints, 150.0);
      const auto ideal = machine::tool_pose(model, machine::Machine::Ideal, q, 150.0);
      tip = std::max(tip, (real.tip_mm - ideal.tip_mm).norm());
      direction = std::max(direction, real.direction.cross(ideal.direction).norm());
    }
    EXPECT_EQ(moved, 0.0) << name;
    EXPECT_LT(tip, 1e-9) << name;
    EXPECT_GT(direction, 1e-6) << name << ": the orientation error is left";
  }
}

// Without thermal the temperatures are their references, whatever they were.
TEST(TermTypes, WithoutThermalTheTemperaturesAreTheReferences) {
  const Model model = machine::load_machine(test::machine_path("mc300_thermal"));
  ASSERT_FALSE(model.temperatures.empty());
  machine::Conditions c = model.reference_conditions();
  model.set_temperature(c, model.temperatures[0].name, model.temperatures[0].reference_degC + 5.0);
  machine::apply_selection(model, machine::parse_type_selection("L-VOL"), c);
  EXPECT_EQ(c.temperature_degC[0], model.temperatures[0].reference_degC);
  machine::apply_selection(model, machine::parse_type_selection("L-VOL,thermal"), c);
  EXPECT_EQ(c.temperature_degC[0], model.temperatures[0].reference_degC);  // kept, not set
}

TEST(TermTypes, TheListReadsCodesAndCompositesInAnyCase) {
  const TypeSelection s = machine::parse_type_selection(" l-pos , R-POS,thermal");
  EXPECT_EQ(s.to_string(), "L-POS, R-POS, thermal");
  EXPECT_EQ(machine::parse_type_selection("L-VOL+").to_string(), "L-POS, L-STR, L-SQU, L-ANG, FOR");
  EXPECT_EQ(machine::parse_type_selection("R-VOL").to_string(), "R-POS, R-RAX, R-POR, R-ANG");
  EXPECT_EQ(machine::parse_type_selection("all").to_string(), "all");
  EXPECT_TRUE(machine::parse_type_selection("L-VOL+,R-VOL+,L-SPEC,R-SPEC,thermal").is_all());
  for (int t = 0; t < machine::kBasicTypeCount; ++t)
    EXPECT_EQ(machine::basic_type_code(static_cast<BasicType>(t)), kBasicCodes[t]);
}

TEST(TermTypes, AnUnknownCodeIsRefusedByName) {
  try {
    machine::parse_type_selection("L-POS,L-PSO");
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'L-PSO' is no compensation type"), std::string::npos) << e.what();
  }
  EXPECT_THROW(machine::parse_type_selection(" , "), std::invalid_argument);
}

}  // namespace
}  // namespace vc
