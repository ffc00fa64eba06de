// Calibration YAML files: the project's rig.yaml, EuRoC sensor.yaml, Kalibr camchain, imu and lidar-imu
// files (io/calibration_io.h, io/euroc_calibration.h, io/kalibr_calibration.h); byte 0 picks the reader.
#include "entry_util.h"
#include "io/calibration_io.h"
#include "io/euroc_calibration.h"
#include "io/kalibr_calibration.h"

namespace vilslam::fuzz {

Outcome calibration_yaml(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return kEmptyInput;
  const std::string path = write_temp_file("calibration.yaml", data + 1, size - 1);
  return outcome_of([&] {
    switch (data[0] % 7) {
      case 0:
        read_rig_yaml(path);
        break;
      case 1:
        read_euroc_camera_yaml(path);
        break;
      case 2:
        read_euroc_imu_yaml(path);
        break;
      case 3:
        read_euroc_lidar_yaml(path);
        break;
      case 4:
        read_euroc_T_BS(path);
        break;
      case 5:
        read_kalibr_camchain(path, path);  // as camchain and as imu.yaml: both are maps of their own keys
        break;
      default: {
        RigCalibration calib;
        read_lidar_imu_yaml(path, calib);
      }
    }
  });
}

}  // namespace vilslam::fuzz
