#pragma once
// Numbers as text, the same way in every message, help text, report and
// file that shows them.
#include <string>

namespace raycache {

// `value` with exactly `decimals` digits after the point ("26.6"), as
// printf's "%.*f".
std::string formatFixed(double value, int decimals);

// `value` with six significant digits, trailing zeros dropped ("0.05",
// "32", "1e+06"), as printf's "%g": short numbers for messages.
std::string formatGeneral(double value);

// The shortest text that reads back as the same double ("-1", "0.25",
// "1e+39"), except that whole numbers are written out ("1000000", not
// "1e+06").
std::string formatShortest(double value);
// The same for a float: the shortest text that reads back as that float
// ("0.05", "3e+38", not the double 3.0000000054977558e+38).
std::string formatShortestFloat(float value);

}  // namespace raycache
