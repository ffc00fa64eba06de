// The vocabulary file of loop closure (loop/vocabulary.h); a vocabulary that loads must also look words up.
#include "entry_util.h"
#include "loop/vocabulary.h"

namespace vilslam::fuzz {

Outcome vocabulary(const std::uint8_t* data, std::size_t size) {
  const std::string path = write_temp_file("vocabulary.voc", data, size);
  return outcome_of([&] {
    const Vocabulary voc = Vocabulary::load(path);
    OrbDescriptor descriptor{};
    voc.word_of(descriptor);
    descriptor.fill(0xff);
    voc.word_of(descriptor);
  });
}

}  // namespace vilslam::fuzz
