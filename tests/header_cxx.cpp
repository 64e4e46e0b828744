// header_cxx.cpp - pw85.h compiles as C++11 (-pedantic -Wall -Wextra -Werror,
// see tests/meson.build) and declares every function with C linkage.
//
// C linkage: the address of every public function is taken below, so this
// program references their unmangled names; had the header left one outside
// extern "C", the link against libpw85 would fail. The exact C types are
// checked by static_assert against extern "C" typedefs.
#include <pw85.h>

#include <cstdio>
#include <cstring>
#include <type_traits>

extern "C" {
typedef const char *version_fn(void);
typedef const char *strerror_fn(int);
typedef void cholesky_decomp_fn(const double *, double *);
typedef void cholesky_solve_fn(const double *, const double *, double *);
typedef void spheroid_fn(double, double, const double *, double *);
typedef int ellipsoid_fn(const double *, const double *, double *);
typedef double f_neg_fn(double, const double *);
typedef void residual_fn(double, const double *, const double *, const double *, double *);
typedef int contact_function_fn(const double *, const double *, const double *, double *);
}

static_assert(std::is_same<decltype(&pw85_version), version_fn *>::value, "pw85_version");
static_assert(std::is_same<decltype(&pw85_strerror), strerror_fn *>::value, "pw85_strerror");
static_assert(std::is_same<decltype(&pw85__cholesky_decomp), cholesky_decomp_fn *>::value,
              "pw85__cholesky_decomp");
static_assert(std::is_same<decltype(&pw85__cholesky_solve), cholesky_solve_fn *>::value,
              "pw85__cholesky_solve");
static_assert(std::is_same<decltype(&pw85_spheroid), spheroid_fn *>::value, "pw85_spheroid");
static_assert(std::is_same<decltype(&pw85_ellipsoid), ellipsoid_fn *>::value, "pw85_ellipsoid");
static_assert(std::is_same<decltype(&pw85_f_neg), f_neg_fn *>::value, "pw85_f_neg");
static_assert(std::is_same<decltype(&pw85__residual), residual_fn *>::value, "pw85__residual");
static_assert(std::is_same<decltype(&pw85_contact_function), contact_function_fn *>::value,
              "pw85_contact_function");

// The header's helper macros stay usable and do not leak into C++ as
// anything but PW85_-prefixed names.
static_assert(PW85_DIM == 3 && PW85_SYM == 6, "dimensions");
#if defined(DIM) || defined(SYM) || defined(min) || defined(max)
#error "pw85.h defines an unprefixed macro"
#endif

int main() {
  // volatile: keep every reference, so that each symbol must resolve.
  void (*volatile functions[])() = {
      reinterpret_cast<void (*)()>(&pw85_version),
      reinterpret_cast<void (*)()>(&pw85_strerror),
      reinterpret_cast<void (*)()>(&pw85__cholesky_decomp),
      reinterpret_cast<void (*)()>(&pw85__cholesky_solve),
      reinterpret_cast<void (*)()>(&pw85_spheroid),
      reinterpret_cast<void (*)()>(&pw85_ellipsoid),
      reinterpret_cast<void (*)()>(&pw85_f_neg),
      reinterpret_cast<void (*)()>(&pw85__residual),
      reinterpret_cast<void (*)()>(&pw85_contact_function),
  };
  for (auto f : functions) {
    if (f == nullptr) return 1;
  }
  if (std::strcmp(pw85_version(), PW85_VERSION) != 0) return 1;
  std::printf("ok - pw85.h as C++11: %zu functions with C linkage\n",
              sizeof functions / sizeof functions[0]);
  return 0;
}
