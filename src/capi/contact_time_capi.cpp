// extern "C" layer of pw85_contact_time (docs/contact_time.md): validation
// and status mapping; the work is in src/core/contact_time/.
#include <cmath>

#include "pw85.h"
#include "common/sym3.hpp"
#include "contact_time/contact_time.hpp"
#include "validate.hpp"

extern "C" {

int pw85_contact_time_ex(double const r12[PW85_DIM], double const v12[PW85_DIM],
                         double const q1[PW85_SYM], double const w1[PW85_DIM],
                         double const q2[PW85_SYM], double const w2[PW85_DIM], double t_max,
                         double *t, int *evaluations) {
  if (t == nullptr) return PW85_ERR_INVALID_ARGUMENT;
  int status = pw85::capi::validate_pair(r12, q1, q2);
  if (status == PW85_OK &&
      (v12 == nullptr || w1 == nullptr || w2 == nullptr || !pw85::all_finite(v12, 3) ||
       !pw85::all_finite(w1, 3) || !pw85::all_finite(w2, 3) || !std::isfinite(t_max) ||
       !(t_max > 0.0)))
    status = PW85_ERR_INVALID_ARGUMENT;
  pw85::ContactTimeResult res{std::nan(""), 0};
  if (status == PW85_OK)
    status = pw85::contact_time(pw85::load_vec3(r12), pw85::load_vec3(v12), pw85::load_sym3(q1),
                                pw85::load_vec3(w1), pw85::load_sym3(q2), pw85::load_vec3(w2),
                                t_max, res);
  if (status == PW85_ERR_INVALID_ARGUMENT) res.t = std::nan("");
  *t = res.t;
  if (evaluations != nullptr) *evaluations = res.evaluations;
  return status;
}

int pw85_contact_time(double const r12[PW85_DIM], double const v12[PW85_DIM],
                      double const q1[PW85_SYM], double const w1[PW85_DIM],
                      double const q2[PW85_SYM], double const w2[PW85_DIM], double t_max,
                      double *t) {
  return pw85_contact_time_ex(r12, v12, q1, w1, q2, w2, t_max, t, nullptr);
}

}  // extern "C"
