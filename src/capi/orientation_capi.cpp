// extern "C" entry points of the orientation constructors and their inverse
// (src/core/common/orientation.cpp): validate, call the core, write the
// outputs only after every input is read (outputs may alias inputs).
#include "pw85.h"

#include "common/ellipsoid.hpp"
#include "common/orientation.hpp"
#include "validate.hpp"

using pw85::capi::fill_nan;

int pw85_ellipsoid_quat(double const radii[PW85_DIM], double const quat[4], double q[PW85_SYM]) {
  if (q == nullptr) return PW85_ERR_INVALID_ARGUMENT;
  if (radii == nullptr || quat == nullptr || !pw85::all_finite(radii, PW85_DIM) ||
      !pw85::all_finite(quat, 4)) {
    fill_nan(q, PW85_SYM);
    return PW85_ERR_INVALID_ARGUMENT;
  }
  double const qt[4] = {quat[0], quat[1], quat[2], quat[3]};
  pw85::Sym3 s;
  int const status = pw85::ellipsoid_quat(pw85::load_vec3(radii), qt, s);
  if (status != PW85_OK) {
    fill_nan(q, PW85_SYM);
    return status;
  }
  for (int i = 0; i < PW85_SYM; ++i) q[i] = s[i];
  return PW85_OK;
}

int pw85_ellipsoid_rotation(double const radii[PW85_DIM], double const rot[PW85_DIM * PW85_DIM],
                            double q[PW85_SYM]) {
  if (q == nullptr) return PW85_ERR_INVALID_ARGUMENT;
  if (rot == nullptr || !pw85::all_finite(rot, PW85_DIM * PW85_DIM)) {
    fill_nan(q, PW85_SYM);
    return PW85_ERR_INVALID_ARGUMENT;
  }
  // The body axes are the columns of rot: the rows of its transpose, the
  // layout of pw85_ellipsoid (which checks radii and the rest).
  double axes[9];
  for (int i = 0; i < PW85_DIM; ++i)
    for (int j = 0; j < PW85_DIM; ++j) axes[3 * j + i] = rot[3 * i + j];
  return pw85_ellipsoid(radii, axes, q);
}

int pw85_ellipsoid_axes(double const q[PW85_SYM], double radii[PW85_DIM],
                        double rot[PW85_DIM * PW85_DIM], double quat[4]) {
  auto fail = [&](int status) {
    if (radii != nullptr) fill_nan(radii, PW85_DIM);
    if (rot != nullptr) fill_nan(rot, PW85_DIM * PW85_DIM);
    if (quat != nullptr) fill_nan(quat, 4);
    return status;
  };
  if (q == nullptr || radii == nullptr || !pw85::all_finite(q, PW85_SYM))
    return fail(PW85_ERR_INVALID_ARGUMENT);
  if (!pw85::positive_definite(q)) return fail(PW85_ERR_NOT_SPD);
  pw85::Sym3 const s = pw85::load_sym3(q);
  pw85::Vec3 r;
  double rt[9], qt[4];
  int const status = pw85::ellipsoid_axes(s, r, rt, qt);
  if (status != PW85_OK && status != PW85_ERR_NO_CONVERGENCE) return fail(status);
  for (int i = 0; i < PW85_DIM; ++i) radii[i] = r[i];
  if (rot != nullptr)
    for (int i = 0; i < 9; ++i) rot[i] = rt[i];
  if (quat != nullptr)
    for (int i = 0; i < 4; ++i) quat[i] = qt[i];
  return status;
}
