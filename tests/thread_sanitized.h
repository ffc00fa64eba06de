#pragma once
// Whether this is a ThreadSanitizer build (scripts/test --tsan): its code runs 5-15 times slower, and what
// links its archives needs -fsanitize=thread too.
namespace vilslam::test {

#if defined(__SANITIZE_THREAD__)
constexpr bool kThreadSanitized = true;
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
constexpr bool kThreadSanitized = true;
#else
constexpr bool kThreadSanitized = false;
#endif
#else
constexpr bool kThreadSanitized = false;
#endif

}  // namespace vilslam::test
