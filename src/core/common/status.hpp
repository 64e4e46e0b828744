// Status codes of the core. The C layer (src/capi) checks with static_assert
// that they equal the PW85_* macros of include/pw85.h.
#pragma once

namespace pw85 {

enum Status : int {
  kOk = 0,
  kInvalidArgument = -1,
  kNotSpd = -2,
  kNoConvergence = -3,
  kNotOrthonormal = -4,
  kUnknownMethod = -5,
  kInaccurate = -6,
  kRange = -7,
  kCapacity = -8,
  kNoMemory = -9,
};

}  // namespace pw85
