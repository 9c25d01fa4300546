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
  const std::vector<std::string> files = {args.a, args.b};
  const auto a = parse_nc(read_nc_text(files[0]), files[0]);
  const auto b = parse_nc(read_nc_text(files[1]), files[1]);
  const NcDiffResult r = nc_diff(a, files[0], b, files[1], o);
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
