#pragma once

namespace lodestone::datasets {

/** Pinhole intrinsics [px]. */
struct PinholeIntrinsics {
    double fx{525.0}, fy{525.0}, cx{319.5}, cy{239.5};
};

}  // namespace lodestone::datasets
