// Constants of IEEE-754 binary64 arithmetic (round to nearest), defined once
// for the whole core: error bounds are written in units of kU.
#pragma once

namespace pw85 {

constexpr double kU = 0x1p-53;                     // unit roundoff u
constexpr double kEps = 0x1p-52;                   // machine epsilon 2u (DBL_EPSILON)
constexpr double kMinNormal = 0x1p-1022;           // smallest positive normal double
constexpr double kMaxDouble = 0x1.fffffffffffffp1023;  // largest finite double (DBL_MAX)

}  // namespace pw85
