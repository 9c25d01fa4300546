// freeturn ncdiff A B: semantic comparison of two NC programs (for CI's golden files).
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "commands.hpp"
#include "freeturn/freeturn.hpp"
#include "freeturn/io/nc_program.hpp"

namespace freeturn::cli {

int run_ncdiff(const NcDiffArgs& args) {
  NcDiffOptions o;
  o.axis_tolerance = args.tolerance;
  // Each program with the child files it calls, as the controller runs them.
  const NcDiffResult r = nc_diff_files(args.a, args.b, o);
  if (!args.quiet) {
    std::printf("%ld blocks vs %ld blocks\n", r.blocks_a, r.blocks_b);
    for (char l : std::string("XZCBF"))
      if (r.largest[l - 'A'] > 0) std::printf("largest |Δ%c| %.3g\n", l, r.largest[l - 'A']);
  }
  if (r.same) {
    if (!args.quiet) std::printf("same within %.3g\n", o.axis_tolerance);
    return kExitOk;
  }
  std::printf("first difference: %s\n", r.first_difference.c_str());
  return kExitCheckFailed;
}

}  // namespace freeturn::cli
