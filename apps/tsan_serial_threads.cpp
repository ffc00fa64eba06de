// Linked into every binary of a ThreadSanitizer build (VILSLAM_TSAN, scripts/test --tsan) and nowhere else.
// ThreadSanitizer cannot see the synchronization inside TBB's and OpenCV's own thread pools (their libraries are
// not instrumented), so each of their parallel loops would be reported as a race that is not there. Here they
// run on the calling thread; the threads vilslam starts itself (pipeline/stage.h), which are what TSan checks,
// are unaffected.
#include <opencv2/core/utility.hpp>
#include <tbb/global_control.h>

namespace {

struct SerialLibraryThreads {
  SerialLibraryThreads() : tbb_serial(tbb::global_control::max_allowed_parallelism, 1) { cv::setNumThreads(0); }
  tbb::global_control tbb_serial;
};

const SerialLibraryThreads serial_library_threads;

}  // namespace
