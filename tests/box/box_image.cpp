// Driver of tests/box/check_box.py: reads lines of nine doubles as 16-digit
// hexadecimal bit patterns (Lx Ly Lz xy xz yz dx dy dz), writes for each
// "status x y z" (bit patterns): the minimum image of d in that box
// (src/core/batch/box.hpp), or "invalid-box".
#include <cinttypes>
#include <cstdio>
#include <cstring>

#include "batch/box.hpp"

static double from_bits(std::uint64_t b) {
  double x;
  std::memcpy(&x, &b, sizeof x);
  return x;
}

static std::uint64_t to_bits(double x) {
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

int main() {
  std::uint64_t v[9];
  while (std::scanf("%" SCNx64 " %" SCNx64 " %" SCNx64 " %" SCNx64 " %" SCNx64 " %" SCNx64
                    " %" SCNx64 " %" SCNx64 " %" SCNx64,
                    &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &v[6], &v[7], &v[8]) == 9) {
    double box[6], d[3];
    for (int i = 0; i < 6; ++i) box[i] = from_bits(v[i]);
    for (int i = 0; i < 3; ++i) d[i] = from_bits(v[6 + i]);
    pw85::batch::Box b;
    if (!pw85::batch::make_box(box, b)) {
      std::printf("invalid-box\n");
      continue;
    }
    int const s = pw85::batch::minimum_image(b, d);
    std::printf("%d %016" PRIx64 " %016" PRIx64 " %016" PRIx64 "\n", s, to_bits(d[0]),
                to_bits(d[1]), to_bits(d[2]));
  }
  return 0;
}
