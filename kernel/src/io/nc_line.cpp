#include "freeturn/io/nc_line.hpp"

#include <cmath>

namespace freeturn {

void strip_nc_comments(std::string_view line, std::string& code) {
  code.clear();
  int depth = 0;
  for (const char ch : line) {
    if (ch == ';' && depth == 0) break;
    if (ch == '(') ++depth;
    else if (ch == ')' && depth > 0) --depth;
    else if (depth == 0) code += ch;
  }
}

int g_code_modal_group(double value) {
  // G codes are named to a tenth (G38.2, G64.1); another value is no code of the table.
  const double tenths = value * 10;
  if (!(std::abs(tenths - std::round(tenths)) < 1e-9) || !(std::abs(tenths) < 1e4)) return -1;
  switch (std::lround(tenths)) {
    case 0:
    case 10:
    case 20:
    case 30:
    case 330:
    case 382:
    case 383:
    case 384:
    case 385:
    case 730:
    case 760:
    case 800:
    case 810:
    case 820:
    case 830:
    case 840:
    case 850:
    case 860:
    case 870:
    case 880:
    case 890:
      return 1;  // motion
    case 170:
    case 180:
    case 190:
    case 171:
    case 181:
    case 191:
      return 2;  // plane
    case 900:
    case 910:
      return 3;  // distance
    case 901:
    case 911:
      return 4;  // arc distance
    case 930:
    case 940:
    case 950:
      return 5;  // feed-rate mode
    case 200:
    case 210:
      return 6;  // units
    case 400:
    case 410:
    case 420:
    case 411:
    case 421:
      return 7;  // cutter compensation
    case 430:
    case 431:
    case 490:
      return 8;  // tool length offset
    case 980:
    case 990:
      return 10;  // canned-cycle return
    case 540:
    case 550:
    case 560:
    case 570:
    case 580:
    case 590:
    case 591:
    case 592:
    case 593:
      return 12;  // coordinate system
    case 610:
    case 611:
    case 640:
      return 13;  // path control
    case 960:
    case 970:
      return 14;  // spindle-speed mode
    case 70:
    case 80:
      return 15;  // lathe diameter or radius
    default:
      return -1;
  }
}

const char* g_code_modal_group_name(int group) {
  switch (group) {
    case 1:
      return "motion";
    case 2:
      return "plane";
    case 3:
      return "distance mode";
    case 4:
      return "arc distance mode";
    case 5:
      return "feed-rate mode";
    case 6:
      return "units";
    case 7:
      return "cutter compensation";
    case 8:
      return "tool length offset";
    case 10:
      return "canned-cycle return";
    case 12:
      return "coordinate system";
    case 13:
      return "path control";
    case 14:
      return "spindle-speed mode";
    case 15:
      return "diameter or radius mode";
    default:
      return "no";
  }
}

}  // namespace freeturn
