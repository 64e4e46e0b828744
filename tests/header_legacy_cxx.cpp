// pw85_legacy.h compiles as C++11 (-pedantic -Werror) and its functions have
// C linkage (this program links against the C symbols).
#include <cmath>

#include <pw85_legacy.h>

int main() {
  double const q1[PW85_SYM] = {1.0, 0.0, 0.0, 1.0, 0.0, 1.0};
  double const q2[PW85_SYM] = {4.0, 0.0, 0.0, 4.0, 0.0, 4.0};
  double const r12[PW85_DIM] = {3.0, 0.0, 0.0};
  double out[2];
  if (pw85_legacy_contact_function1(r12, q1, q2, out) != PW85_OK) return 1;
  if (std::fabs(out[0] - 1.0) > 1e-14) return 2;
  if (pw85_legacy_contact_function2(r12, q1, q2, out) != PW85_OK) return 3;
  if (std::fabs(out[0] - 1.0) > 1e-14) return 4;
  return std::isnan(pw85_legacy__det_sym(nullptr)) ? 0 : 5;
}
