// Measures the default pocket model's windows (planner/pocket_model.h: DefaultTable(),
// default SimParams and Options) and prints planner/pocket_model_default.cc, which
// compiles them in. Exact: the numbers are printed as hexadecimal floats.
// Usage: pocket_windows > planner/pocket_model_default.cc (scripts/pocket-windows)
#include <cstdio>

#include "physics/sim/sim_params.h"
#include "physics/table/table.h"
#include "planner/pocket_model.h"

int main() {
  using snooker::planner::PocketModel;
  const PocketModel model(snooker::physics::DefaultTable(), snooker::physics::SimParams{}, PocketModel::Options{});
  std::printf(
      "// The default pocket model's windows (PocketModel::Default()): DefaultTable(), default\n"
      "// SimParams and Options, measured by the simulator (%ld single-ball simulations).\n"
      "// Written by scripts/pocket-windows; do not edit. PocketModelTest measures them again.\n"
      "#include <iterator>\n\n"
      "#include \"planner/pocket_model.h\"\n\n"
      "namespace snooker::planner {\n"
      "namespace {\n\n"
      "// {lo, hi, empty}: the corners' grid, then the middles', each by speed, then by angle.\n"
      "constexpr PocketWindow kCells[] = {\n",
      model.simulations());
  for (const auto& w : model.Cells()) {
    std::printf("    {%a, %a, %s},\n", w.lo, w.hi, w.empty ? "true" : "false");
  }
  std::printf(
      "};\n\n"
      "}  // namespace\n\n"
      "std::vector<PocketWindow> PocketModel::DefaultCells() { return {std::begin(kCells), std::end(kCells)}; }\n\n"
      "}  // namespace snooker::planner\n");
  return 0;
}
