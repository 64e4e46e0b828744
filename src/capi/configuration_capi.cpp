// extern "C" layer of the scene object (pw85_configuration_*): checks the
// pointers, calls src/core/batch/scene.cpp, maps the core's statuses.
#include <cstdlib>
#include <new>

#include "pw85.h"
#include "batch/scene.hpp"

static_assert(pw85::kCapacity == PW85_ERR_CAPACITY, "");
static_assert(pw85::kNoMemory == PW85_ERR_NO_MEMORY, "");

struct pw85_configuration {
  pw85::Scene scene;
};

extern "C" {

int pw85_configuration_create(long long n, double const *centres, double const *q,
                              double const box[6], pw85_configuration **configuration,
                              long long *bad) {
  if (bad) *bad = -1;
  if (configuration == nullptr || (n > 0 && (centres == nullptr || q == nullptr)))
    return PW85_ERR_INVALID_ARGUMENT;
  void *mem = std::malloc(sizeof(pw85_configuration));
  if (mem == nullptr) return PW85_ERR_NO_MEMORY;
  auto *c = new (mem) pw85_configuration();
  long long b = -1;
  int const s = pw85::scene_assign(c->scene, n, centres, q, box, b);
  if (s != PW85_OK) {
    pw85::scene_release(c->scene);
    std::free(mem);
    if (bad) *bad = b;
    return s;
  }
  *configuration = c;
  return PW85_OK;
}

void pw85_configuration_destroy(pw85_configuration *configuration) {
  if (configuration == nullptr) return;
  pw85::scene_release(configuration->scene);
  std::free(configuration);
}

int pw85_configuration_update(pw85_configuration *configuration, long long n,
                              double const *centres, double const *q, double const box[6],
                              long long *bad) {
  if (bad) *bad = -1;
  if (configuration == nullptr || (n > 0 && (centres == nullptr || q == nullptr)))
    return PW85_ERR_INVALID_ARGUMENT;
  long long b = -1;
  int const s = pw85::scene_assign(configuration->scene, n, centres, q, box, b);
  if (s != PW85_OK && bad) *bad = b;
  return s;
}

long long pw85_configuration_size(pw85_configuration const *configuration) {
  return configuration == nullptr ? -1 : configuration->scene.n;
}

int pw85_configuration_pairs(pw85_configuration const *configuration, double s, int nthreads,
                             long long capacity, long long *i, long long *j, double *mu2,
                             long long *count, long long examined[2]) {
  if (configuration == nullptr || count == nullptr || capacity < 0 ||
      (capacity > 0 && (i == nullptr || j == nullptr)))
    return PW85_ERR_INVALID_ARGUMENT;
  long long m = 0;
  long long ex[2] = {0, 0};
  int const st = pw85::scene_pairs(configuration->scene, s, nthreads, capacity, i, j, mu2, m, ex);
  if (st == PW85_OK || st == PW85_ERR_CAPACITY) {
    *count = m;
    if (examined) {
      examined[0] = ex[0];
      examined[1] = ex[1];
    }
  }
  return st;
}

int pw85_configuration_test_move(pw85_configuration const *configuration, long long i,
                                 double const centre[3], double const q[6], long long *j) {
  if (configuration == nullptr || centre == nullptr || q == nullptr || j == nullptr)
    return PW85_ERR_INVALID_ARGUMENT;
  return pw85::scene_test_move(configuration->scene, i, centre, q, *j);
}

int pw85_configuration_neighbours(pw85_configuration const *configuration, long long i,
                                  double distance, long long capacity, long long *j,
                                  long long *count) {
  if (configuration == nullptr || count == nullptr || capacity < 0 ||
      (capacity > 0 && j == nullptr))
    return PW85_ERR_INVALID_ARGUMENT;
  long long m = 0;
  int const st = pw85::scene_neighbours(configuration->scene, i, distance, capacity, j, m);
  if (st == PW85_OK || st == PW85_ERR_CAPACITY) *count = m;
  return st;
}

int pw85_configuration_move(pw85_configuration *configuration, long long i,
                            double const centre[3], double const q[6]) {
  if (configuration == nullptr || centre == nullptr || q == nullptr)
    return PW85_ERR_INVALID_ARGUMENT;
  return pw85::scene_move(configuration->scene, i, centre, q);
}

}  // extern "C"
