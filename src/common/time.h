#pragma once
// Time is int64 nanoseconds everywhere (`t_ns`); seconds only at the edges (file formats, printing).
#include <cmath>
#include <cstdint>

namespace vilslam {

using TimeNs = std::int64_t;

constexpr TimeNs kNsPerSecond = 1'000'000'000;

inline double ns_to_s(TimeNs t_ns) { return static_cast<double>(t_ns) * 1e-9; }
inline TimeNs s_to_ns(double t_s) { return static_cast<TimeNs>(std::llround(t_s * 1e9)); }

}  // namespace vilslam
