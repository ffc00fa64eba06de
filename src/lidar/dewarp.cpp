#include "lidar/dewarp.h"

namespace vilslam::lidar {

namespace {

// (T_{k+1})^-1 T_i for the instant t_ns, reusing the last result while consecutive points share a time.
class ToEndFrame {
 public:
  ToEndFrame(const PoseAtTime& T_W_L, TimeNs end_t_ns) : T_W_L_(T_W_L), T_end_W_(T_W_L(end_t_ns).inverse()) {}

  const SE3& at(TimeNs t_ns) {
    if (!have_last_ || last_t_ns_ != t_ns) {
      T_end_i_ = T_end_W_ * T_W_L_(t_ns);
      last_t_ns_ = t_ns;
      have_last_ = true;
    }
    return T_end_i_;
  }

 private:
  const PoseAtTime& T_W_L_;
  SE3 T_end_W_;
  SE3 T_end_i_;
  TimeNs last_t_ns_ = 0;
  bool have_last_ = false;
};

void dewarp_points(std::vector<FeaturePoint>& points, TimeNs scan_t_ns, TimeNs end_t_ns, ToEndFrame& to_end) {
  const float end_offset_s = static_cast<float>(ns_to_s(end_t_ns - scan_t_ns));
  for (FeaturePoint& f : points) {
    // Paper eq. (dewarping): P~_i = (T^L_{k+1})^-1 T^L_i P_i.
    const SE3& T_end_i = to_end.at(scan_t_ns + s_to_ns(f.t_offset_s));
    f.p_L = T_end_i * f.p_L;
    f.normal_L = T_end_i.rotation() * f.normal_L;
    f.t_offset_s = end_offset_s;
  }
}

}  // namespace

FeatureScan dewarp(const FeatureScan& features, TimeNs end_t_ns, const PoseAtTime& T_W_L) {
  FeatureScan out = features;
  ToEndFrame to_end(T_W_L, end_t_ns);
  dewarp_points(out.edges, features.t_ns, end_t_ns, to_end);
  dewarp_points(out.surfaces, features.t_ns, end_t_ns, to_end);
  return out;
}

LidarScan dewarp(const LidarScan& scan, const PoseAtTime& T_W_L) {
  LidarScan out = scan;
  const TimeNs end_t_ns = scan.end_t_ns();
  const float end_offset_s = static_cast<float>(ns_to_s(end_t_ns - scan.t_ns));
  ToEndFrame to_end(T_W_L, end_t_ns);
  for (LidarPoint& p : out.points) {
    // Paper eq. (dewarping): P~_i = (T^L_{k+1})^-1 T^L_i P_i.
    const Vec3 p_end = to_end.at(scan.t_ns + s_to_ns(p.t_offset_s)) * Vec3(p.x, p.y, p.z);
    p.x = static_cast<float>(p_end.x());
    p.y = static_cast<float>(p_end.y());
    p.z = static_cast<float>(p_end.z());
    p.t_offset_s = end_offset_s;
  }
  return out;
}

}  // namespace vilslam::lidar
